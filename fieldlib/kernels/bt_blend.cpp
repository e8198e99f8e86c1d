#include "kernels/bt_blend.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

std::vector<double> BtCombination::constants(bool conic, int tau, const std::vector<int>& sigma,
                                             const std::vector<double>& r,
                                             const std::vector<double>& p,
                                             const std::vector<double>& m) {
  const size_t k = m.size();
  std::vector<double> c = {conic ? 1.0 : 0.0, static_cast<double>(tau), static_cast<double>(k)};
  for (int s : sigma) c.push_back(s);
  for (size_t i = 0; i < k; ++i) c.push_back(r[i]);
  for (size_t i = 0; i < k; ++i) c.push_back(i < p.size() ? p[i] : 0.0);
  for (double mi : m) c.push_back(mi);
  return c;
}

double BtCombination::base(const double* x, double* dx) const {
  if (conic) return bt2_conic(x, r[0], r[1], p[0], m, dx);
  return bt_hyper(x, k, r, p, m, dx, nullptr);
}

double BtCombination::value(const double* f, double* df) const {
  Slots<double> x(k);
  for (int i = 0; i < k; ++i) x.set(i, sigma[i] * f[i]);
  const double v = base(x.data(), df);
  if (df)
    for (int i = 0; i < k; ++i) df[i] *= tau * sigma[i];
  return tau * v;
}

}  // namespace softtrace

#include "kernels/bt_blend.h"

#include <algorithm>
#include <cmath>

#include "kernels/bt_base.h"
#include "math/scratch.h"

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

Interval BtCombination::bounds(const Interval* I, const double* L, const Interval* D,
                               double* lipschitz, Interval* slope) const {
  Slots<double> lo(k), hi(k);  // the ends of X_i = σ_i [f_i]
  for (int i = 0; i < k; ++i) {
    lo.set(i, sigma[i] > 0 ? I[i].lo : -I[i].hi);
    hi.set(i, sigma[i] > 0 ? I[i].hi : -I[i].lo);
  }
  // BT is non-decreasing in every x_i ([BT-5]): its range is between its values at the ends,
  // each padded by twice the root finder's tolerance (the end's error and the sample's).
  const double vlo = base(lo.data(), nullptr), vhi = base(hi.data(), nullptr);
  const Interval bt = iv::out(vlo - 2 * bt_value_tolerance(lo.data(), k, vlo, r, m),
                              vhi + 2 * bt_value_tolerance(hi.data(), k, vhi, r, m));
  double Lr = 0;
  Interval s{0, 0};
  bool any = false;
  for (int i = 0; i < k; ++i) {
    if (!bt_can_be_active(i, k, lo.data(), hi.data(), r, m, m)) continue;
    Lr = std::max(Lr, iv::up(L[i] / m[i]));
    if (!D) continue;
    // τσ_i [f_i']/m_i, rounded outward
    const Interval d = tau * sigma[i] > 0 ? D[i] : -D[i];
    const Interval q = iv::out(d.lo / m[i], d.hi / m[i]);
    s = any ? hull(s, q) : q;
    any = true;
  }
  *lipschitz = Lr;
  if (D) *slope = s;
  return tau > 0 ? bt : -bt;
}

}  // namespace softtrace

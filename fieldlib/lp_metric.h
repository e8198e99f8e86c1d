// The LP metric (|x/a|^n + |y/b|^n + |z/c|^n)^(1/n) (000 Eq. 2, docs/math.md §2.5) as kernels
// shared by the model node (distances_gauge.cpp) and the program's LpMetric instruction, so both
// compute the same bits. Bounds over a box: f is non-decreasing in every |x_i/a_i|, so its interval
// is f at the ends of the terms' intervals; |∂f/∂x_i| = (u_i/f)^(n-1)/a_i is bounded by
// power_sum_partial_bound, and the global bound (gauge_lipschitz) caps the result.
#pragma once

#include <algorithm>
#include <cmath>

#include "box.h"
#include "gauge.h"
#include "node_util.h"
#include "one_sided.h"

namespace softtrace {

struct LpMetricParams {
  Vec3 a;
  double n, global_L;
};

inline double lp_metric(const LpMetricParams& m, const Vec3& p, Vec3* grad) {
  const Vec3& a = m.a;
  if (m.n == 2) {
    // Ellipsoids (most blobs): the plain root where the squares can neither overflow nor lose
    // precision to subnormals; power_sum's scaling by the largest term only outside that range.
    // ∂f/∂x_i = (x_i/a_i)/(a_i f), computed as power_sum's (u_i/f)·sgn(x_i)/a_i would be.
    const double x = p.x / a.x, y = p.y / a.y, z = p.z / a.z, s = x * x + y * y + z * z;
    if (s > 1e-280 && s < 1e280) {
      const double f = std::sqrt(s);
      if (grad) *grad = {x / f / a.x, y / f / a.y, z / f / a.z};
      return f;
    }
  }
  const double u[3] = {std::abs(p.x / a.x), std::abs(p.y / a.y), std::abs(p.z / a.z)};
  double du[3];
  const double f = power_sum(u, 3, m.n, grad ? du : nullptr);
  if (grad) *grad = {du[0] * sgn(p.x) / a.x, du[1] * sgn(p.y) / a.y, du[2] * sgn(p.z) / a.z};
  return f;
}

// The value interval and the Lipschitz bound over `b` in one pass. With `rate` (the local
// coordinates' rates along a segment in `b`), also the range of df/dt along it into *slope:
// u_i = |x_i|/a_i is a one-sided term of x_i with both radii a_i, so power_sum_slope over them
// (not capped by the Lipschitz bound).
inline void lp_metric_bounds(const LpMetricParams& m, const Box& b, Interval* value,
                             double* lipschitz, const Interval* rate = nullptr,
                             Interval* slope = nullptr) {
  Interval u[3];
  for (int i = 0; i < 3; ++i) u[i] = abs(b.axis(i)) / Interval(m.a[i]);
  Interval f;
  const double hi2 = u[0].hi * u[0].hi + u[1].hi * u[1].hi + u[2].hi * u[2].hi;
  if (m.n == 2 && hi2 < 1e280) {
    // Ellipsoids without pow: three squares summed and a correctly rounded root err by under
    // 3 ulps (and the point kernel's value by as much), so 2e-15 relative holds both. Squares
    // that underflow only lower the lower end.
    const double lo2 = u[0].lo * u[0].lo + u[1].lo * u[1].lo + u[2].lo * u[2].lo;
    f = {std::sqrt(lo2) * (1 - 2e-15), std::sqrt(hi2) * (1 + 2e-15)};
  } else {
    f = power_sum(u, 3, m.n);
  }
  *value = f;
  if (!lipschitz) return;
  double s = 0;
  for (int i = 0; i < 3; ++i) {
    const double g = power_sum_partial_bound(u[i], f, m.n) / m.a[i];
    s += g * g;
  }
  *lipschitz = std::min(m.global_L, std::sqrt(s) * (1 + 1e-13));
  if (!rate) return;
  Interval du[3];
  for (int i = 0; i < 3; ++i) du[i] = OneSidedTerm{m.a[i], m.a[i], 0}.rate(b.axis(i), rate[i]);
  *slope = power_sum_slope(u, du, 3, f, m.n);
}

}  // namespace softtrace

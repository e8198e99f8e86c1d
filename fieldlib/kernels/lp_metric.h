// The LP metric (|x/a|^n + |y/b|^n + |z/c|^n)^(1/n) (000 Eq. 2, docs/math.md §2.5) as kernels
// shared by the model node (distances_gauge.cpp) and the program's LpMetric instruction, so both
// compute the same bits. Bounds over a box: f is non-decreasing in every |x_i/a_i|, so its interval
// is f at the ends of the terms' intervals; |∂f/∂x_i| = (u_i/f)^(n-1)/a_i is bounded by
// power_sum_partial_bound, and the global bound (gauge_lipschitz) caps the result.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/gauge.h"
#include "kernels/one_sided.h"
#include "math/bound_util.h"
#include "math/box.h"

namespace softtrace {

struct LpMetricParams {
  Vec3 a;
  double n, global_L;
  Vec3 ia;  // 1/a

  // From the program's constants (a, n, global_L, 1/a) and from the node's radii and exponent.
  static LpMetricParams load(const double* k) {
    return {{k[0], k[1], k[2]}, k[3], k[4], {k[5], k[6], k[7]}};
  }
  static LpMetricParams make(const Vec3& a, double n, double global_L) {
    return {a, n, global_L, {1 / a.x, 1 / a.y, 1 / a.z}};
  }
  // The program's constants, in load()'s order.
  std::vector<double> constants() const { return {a.x, a.y, a.z, n, global_L, ia.x, ia.y, ia.z}; }
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

// The Hessian of f = (Σ u_i^n)^(1/n), u_i = |x_i|/a_i: with g = ∇f,
//   ∂²f/∂x_i∂x_j = (n - 1)/f · (δ_ij f^(2-n) u_i^(n-2)/a_i² - g_i g_j)
// (differentiate g_i = (u_i/f)^(n-1) sgn(x_i)/a_i). False at the centre (f = 0) and, for n < 2,
// on a coordinate plane, where u_i^(n-2) is unbounded and f has no Hessian.
inline bool lp_metric_hessian(const LpMetricParams& m, const Vec3& p, Mat3* H) {
  Vec3 g;
  const double f = lp_metric(m, p, &g);
  if (!(f > 0) || !std::isfinite(f)) return false;
  const double n = m.n;
  double d[3];
  for (int i = 0; i < 3; ++i) {
    const double u = std::abs(p[i]) * m.ia[i] / f;  // u_i/f <= 1: no overflow in the power
    if (u == 0 && n < 2) {
      if (n != 1) return false;
      d[i] = 0;  // n = 1: f is linear off the planes, (n - 1) = 0 below
    } else {
      d[i] = (n == 2 ? 1.0 : std::pow(u, n - 2)) * m.ia[i] * m.ia[i];
    }
  }
  const double c = (n - 1) / f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H->r[i][j] = c * ((i == j ? d[i] : 0.0) - g[i] * g[j]);
  return std::isfinite(c);
}

// The terms u_i = |x_i|/a_i over `b`: |x_i| · fl(1/a_i), two roundings of at most 2^-53 relative
// each, so widened by 2^-51 relative (and 2^-1074 for underflow) they hold the exact quotients.
inline void lp_metric_terms(const LpMetricParams& m, const Box& b, Interval* u) {
  for (int i = 0; i < 3; ++i) {
    const Interval x = abs(b.axis(i));
    const double lo = x.lo * m.ia[i], hi = x.hi * m.ia[i];
    u[i] = {std::max(0.0, lo - (lo * 0x1p-51 + 0x1p-1074)), hi + (hi * 0x1p-51 + 0x1p-1074)};
  }
}

// The value interval and the Lipschitz bound over `b` in one pass. With `rate` (the local
// coordinates' rates along a segment in `b`), also the range of df/dt along it into *slope:
// u_i = |x_i|/a_i is a one-sided term of x_i with both radii a_i, so power_sum_slope over them
// (not capped by the Lipschitz bound).
inline void lp_metric_bounds(const LpMetricParams& m, const Box& b, Interval* value,
                             double* lipschitz, const Interval* rate = nullptr,
                             Interval* slope = nullptr) {
  Interval u[3];
  lp_metric_terms(m, b, u);
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
  // The terms' upper partials: the Lipschitz bound's, and the slope's again (not recomputed).
  double partial_hi[3];
  bool partials_known = false;
  if (m.n == 2 && m.a.x == m.a.y && m.a.y == m.a.z) {
    // A ball: |∇(|x|/a)| = 1/a everywhere, the global bound.
    *lipschitz = m.global_L;
  } else {
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      partial_hi[i] = power_sum_partial_bound(u[i], f, m.n);
      const double g = partial_hi[i] / m.a[i];
      s += g * g;
    }
    partials_known = true;
    *lipschitz = std::min(m.global_L, std::sqrt(s) * (1 + 1e-13));
  }
  if (!rate) return;
  Interval du[3];
  for (int i = 0; i < 3; ++i) du[i] = OneSidedTerm{m.a[i], m.a[i], 0}.rate(b.axis(i), rate[i]);
  *slope = partials_known ? power_sum_slope(u, du, 3, f, m.n, partial_hi)
                          : power_sum_slope(u, du, 3, f, m.n);
}

}  // namespace softtrace

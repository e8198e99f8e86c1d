// The super-ellipsoidal (CG Ricci) union and intersection of distance functions (docs/math.md
// §5.3; the bounds are derived in distances_combine.cpp). The kernels are shared by the model
// nodes and the program's SuperUnion and SuperIntersect instructions, so both compute the same
// bits from the children's values, gradients, intervals and Lipschitz bounds.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/gauge.h"
#include "kernels/one_sided.h"
#include "math/interval.h"
#include "math/scratch.h"
#include "math/vec.h"

namespace softtrace {

// (Σ x_i^-n)^(-1/n), 0 when some x_i <= 0 — 000 Eq. 6 B_RU^cg; as m·(Σ (m/x_i)^n)^(-1/n) with
// m = min x_i: every ratio is <= 1, so n = 20 cannot overflow.
inline double super_union(const double* x, size_t k, double n) {
  double m = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < k; ++i) m = std::min(m, x[i]);
  if (!(m > 0)) return 0;
  double s = 0;
  for (size_t i = 0; i < k; ++i) s += std::pow(m / x[i], n);
  return m * std::pow(s, -1 / n);
}

// The union's gradient from the children's gradients g, where it is U: Σ g_i (U/x_i)^(n+1).
inline Vec3 super_union_gradient(const double* x, const Vec3* g, size_t k, double n, double U) {
  Vec3 grad{};
  if (U == 0) {
    // U = x_j on the zero set of child j (the partial (U/x_j)^(n+1) tends to 1 there).
    for (size_t i = 0; i < k; ++i)
      if (x[i] <= 0) return x[i] == 0 ? g[i] : Vec3{};
    return grad;
  }
  for (size_t i = 0; i < k; ++i) grad += g[i] * std::pow(U / x[i], n + 1);
  return grad;
}

// U over the children's intervals x: U is non-decreasing in every x_i, so U at the ends (pow is
// faithfully rounded: widened by a relative margin well above its error).
inline Interval super_union_interval(const Interval* x, size_t k, double n) {
  Scratch<double> lo(k), hi(k);
  for (size_t i = 0; i < k; ++i) {
    lo[i] = std::max(0.0, x[i].lo);
    hi[i] = std::max(0.0, x[i].hi);
  }
  return {std::max(0.0, super_union(lo.data(), k, n) * (1 - 1e-13)),
          super_union(hi.data(), k, n) * (1 + 1e-13)};
}

// |∇U| <= Σ v_i L_i with v_i = (U/x_i)^(n+1) <= min(1, (U_hi/x_i,lo)^(n+1)), and <= max_i L_i
// (Σ v_i <= 1), from the children's intervals x and box bounds L where U lies in `U`.
inline double super_union_lipschitz(const Interval* x, const double* L, size_t k, double n,
                                    Interval U) {
  double sum = 0, L_max = 0;
  for (size_t i = 0; i < k; ++i) {
    const double v = x[i].lo > 0 ? std::min(1.0, std::pow(U.hi / x[i].lo, n + 1)) : 1.0;
    sum += chain(v, L[i]);
    L_max = std::max(L_max, L[i]);
  }
  return std::min(L_max, sum * (1 + 1e-13));
}

// U's slope along a segment (docs/math.md §8, "Slopes along a segment"), from the children's
// ranges x and slopes D there, U in `U`: the chain rule Σ v_i x_i' with v_i = ∂U/∂x_i =
// (U/x_i)^(n+1) between (U_lo/x_i,hi)^(n+1) and min(1, (U_hi/x_i,lo)^(n+1)); where some child may
// be <= 0, U = 0 with slope 0 there and is continuous across, so 0 joins the hull. And since
// v_i >= 0 with Σ v_i <= 1 (the lipschitz bound's argument), U' is a convex combination of 0 and
// the children's slopes: within the hull of 0 and their ends.
inline Interval super_union_slope(const Interval* x, const Interval* D, size_t k, double n,
                                  Interval U) {
  Interval s(0.0);
  double lo = 0, hi = 0;
  bool may_vanish = false;
  for (size_t i = 0; i < k; ++i) {
    const double v_hi =
        x[i].lo > 0 ? std::min(1.0, std::pow(U.hi / x[i].lo, n + 1) * (1 + 1e-13)) : 1.0;
    const double v_lo = x[i].hi > 0 && U.lo > 0
                            ? std::min(v_hi, std::pow(U.lo / x[i].hi, n + 1) * (1 - 1e-13))
                            : 0.0;
    s = s + Interval(v_lo, v_hi) * D[i];
    lo = std::min(lo, D[i].lo);
    hi = std::max(hi, D[i].hi);
    may_vanish = may_vanish || x[i].lo <= 0;
  }
  if (may_vanish) s = hull(s, 0.0);
  return {std::max(s.lo, lo), std::min(s.hi, hi)};
}

// (Σ x_i^n)^(1/n) with x_i clamped at 0 — 000 Eq. 6 B_RI^cg. x holds the children's values and
// is clamped in place; the gradient Σ g_i (x_i/I)^(n-1) into grad when it is non-null.
inline double super_intersection(double* x, const Vec3* g, size_t k, double n, Vec3* grad) {
  Scratch<double> d(k);
  for (size_t i = 0; i < k; ++i) x[i] = std::max(0.0, x[i]);
  const double f = power_sum(x, static_cast<int>(k), n, grad ? d.data() : nullptr);
  if (grad) {
    *grad = {};
    for (size_t i = 0; i < k; ++i) *grad += g[i] * d[i];
  }
  return f;
}

// The intersection's bound over a box from the children's intervals x and box bounds L (f the
// interval of the result, global_L the global bound): the partials' bounds
// (power_sum_partial_bound) against the children's, and for n >= 1 Hölder's (Σ L_i^n)^(1/n).
inline double super_intersection_lipschitz(const Interval* x, const double* L, size_t k, double n,
                                           Interval f, double global_L) {
  double sum = 0;
  for (size_t i = 0; i < k; ++i) sum += chain(power_sum_partial_bound(x[i], f, n), L[i]);
  double bound = sum * (1 + 1e-13);
  if (n >= 1) bound = std::min(bound, power_sum(L, static_cast<int>(k), n, nullptr) * (1 + 1e-13));
  return std::isnan(bound) ? global_L : std::min(global_L, bound);
}

// The intersection's slope along a segment from the children's ranges x and slopes D there, f its
// range: the power sum's (power_sum_slope) of the terms [x_i]_+, whose rate is x_i' where x_i > 0,
// 0 where x_i <= 0 all along, and between the two where it may cross 0 (a kink).
inline Interval super_intersection_slope(const Interval* x, const Interval* D, size_t k, double n,
                                         Interval f) {
  Scratch<Interval> du(k);
  for (size_t i = 0; i < k; ++i)
    du[i] = x[i].lo > 0 ? D[i] : x[i].hi <= 0 ? Interval(0.0) : hull(D[i], 0.0);
  return power_sum_slope(x, du.data(), static_cast<int>(k), f, n);
}

}  // namespace softtrace

// Ricci's super-ellipsoidal operators (docs/math.md §5.3 constructive, §5.4 soft). Every one is a
// power mean B = (Σ g_i^q)^(1/q) with q = n or q = -n of arguments g_i = f_i, 1 - f_i (soft
// complement) or 1/f_i (constructive complement):
//   soft:         union q = n; intersection q = -n; difference q = -n with g = (f1, 1-f2, ...)
//   constructive: union q = -n; intersection q = n; difference q = n with g = (f1, 1/f2, ...)
// Bounds: B is non-decreasing in every g_i, so its interval is B at the ends of the g intervals.
// q = n: ∂B/∂g_i = (g_i/B)^(n-1) (power_sum_partial_bound per box) and, for n >= 1, Hölder with
// Σ (g_i/B)^n = 1 gives |∇B| <= (Σ (c_i L_i)^n)^(1/n) ([RS-3]); n < 1 has no global bound.
// q = -n: ∂B/∂g_i = (B/g_i)^(n+1) <= (B/g_i)^n, which sum to 1, so |∇B| <= max_i c_i L_i, and
// per box Σ min(1, (B.hi/g_i.lo)^(n+1)) c_i L_i. c_i = sup|dg_i/df_i| (1, or 1/f^2 for 1/f).
// The kernels are shared by the model node (blends_ricci.cpp) and the program's Ricci instruction,
// so both compute the same bits from the children's values, gradients, intervals and Lipschitz
// bounds. The complements' values and intervals are complement.h's.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/complement.h"
#include "kernels/gauge.h"
#include "kernels/super_ellipsoidal.h"
#include "math/bound_util.h"
#include "math/interval.h"
#include "math/scratch.h"
#include "math/vec.h"

namespace softtrace {

// The argument g_i made of child i's value: f_i, 1 - f_i or 1/f_i.
enum class RicciArg { Same, SoftComplement, CgComplement };

struct RicciParams {
  bool positive;  // q = n; otherwise q = -n
  double n;
  RicciArg rest;  // the arguments of children 2..k (a difference's); the first child's is f_1
};

inline RicciArg ricci_arg_kind(const RicciParams& m, size_t i) {
  return i == 0 ? RicciArg::Same : m.rest;
}

// g_i from f and dg_i/df into dg.
inline double ricci_arg(const RicciParams& m, size_t i, double f, double* dg) {
  switch (ricci_arg_kind(m, i)) {
    case RicciArg::Same:
      *dg = 1;
      return f;
    case RicciArg::SoftComplement:
      *dg = -1;
      return complement(Convention::Soft, f, nullptr);
    case RicciArg::CgComplement:
      *dg = f <= kCgFloor ? 0 : -1 / (f * f);
      return complement(Convention::Constructive, f, nullptr);
  }
  return f;
}

inline Interval ricci_arg_range(const RicciParams& m, size_t i, Interval f) {
  switch (ricci_arg_kind(m, i)) {
    case RicciArg::Same:
      return f;
    case RicciArg::SoftComplement:
      return complement_interval(Convention::Soft, f);
    case RicciArg::CgComplement:
      return complement_interval(Convention::Constructive, f);
  }
  return f;
}

// c_i = sup |dg_i/df| where f lies in `f`.
inline double ricci_arg_slope(const RicciParams& m, size_t i, Interval f) {
  if (ricci_arg_kind(m, i) != RicciArg::CgComplement) return 1;
  const double lo = std::max(f.lo, kCgFloor);
  return 1 / (lo * lo) * (1 + 1e-12);
}

// B(g) and ∂B/∂g_i into dB when it is non-null; negative arguments count as 0 (q = n) or make
// B = 0 (q = -n, docs/math.md §5.4). q = -n as m·(Σ (m/g_i)^n)^(-1/n), m = min g_i: every ratio
// is <= 1, so no overflow.
inline double ricci_mean(const RicciParams& m, const double* g, size_t k, double* dB) {
  const int kk = static_cast<int>(k);
  if (m.positive) {
    Scratch<double> u(k);
    for (size_t i = 0; i < k; ++i) u[i] = std::max(g[i], 0.0);
    return power_sum(u.data(), kk, m.n, dB);
  }
  double lo = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < k; ++i) lo = std::min(lo, g[i]);
  if (lo <= 0) {
    if (dB) std::fill(dB, dB + k, 0.0);
    return 0;
  }
  double s = 0;
  for (size_t i = 0; i < k; ++i) s += std::pow(lo / g[i], m.n);  // in [1, k]: no overflow
  const double B = lo * std::pow(s, -1 / m.n);
  if (dB)
    for (size_t i = 0; i < k; ++i) dB[i] = std::pow(B / g[i], m.n + 1);
  return B;
}

// The blend of the children's values f (overwritten by the arguments g_i) and, when grad is
// non-null, its gradient Σ ∇f_i (∂B/∂g_i)(dg_i/df_i) from the children's gradients gf. A NaN
// child makes B NaN, and B's NaN is the gradient: a product of two NaNs keeps either's sign, as
// the compiler orders the operands, and the model and the program must agree.
inline double ricci(const RicciParams& m, double* f, const Vec3* gf, size_t k, Vec3* grad) {
  Scratch<double> dg(k), dB(k);
  for (size_t i = 0; i < k; ++i) f[i] = ricci_arg(m, i, f[i], &dg[i]);
  const double B = ricci_mean(m, f, k, grad ? dB.data() : nullptr);
  if (grad && std::isnan(B)) {
    *grad = {B, B, B};
  } else if (grad) {
    *grad = {};
    for (size_t i = 0; i < k; ++i)
      if (dB[i] != 0 && dg[i] != 0) *grad += gf[i] * (dB[i] * dg[i]);
  }
  return B;
}

// B over the arguments' ranges G: B at their ends (pow is faithfully rounded: widened by a
// relative margin well above its error).
inline Interval ricci_range(const RicciParams& m, const Interval* G, size_t k) {
  if (m.positive) return power_sum(G, static_cast<int>(k), m.n);
  Scratch<double> lo(k), hi(k);
  for (size_t i = 0; i < k; ++i) {
    lo[i] = G[i].lo;
    hi[i] = G[i].hi;
  }
  return {std::max(0.0, ricci_mean(m, lo.data(), k, nullptr) * (1 - 1e-13)),
          ricci_mean(m, hi.data(), k, nullptr) * (1 + 1e-13)};
}

// B over a box where the children lie in f.
inline Interval ricci_interval(const RicciParams& m, const Interval* f, size_t k) {
  Scratch<Interval> G(k);
  for (size_t i = 0; i < k; ++i) G[i] = ricci_arg_range(m, i, f[i]);
  return ricci_range(m, G.data(), k);
}

// The derivative-free bound from the c_i L_i: (Σ (c_i L_i)^n)^(1/n) for q = n >= 1 (none below
// 1), max_i c_i L_i for q = -n.
inline double ricci_combine(const RicciParams& m, const double* cL, size_t k) {
  for (size_t i = 0; i < k; ++i)
    if (!std::isfinite(cL[i])) return std::numeric_limits<double>::infinity();
  if (m.positive) {
    if (m.n < 1) return std::numeric_limits<double>::infinity();
    return power_sum(cL, static_cast<int>(k), m.n, nullptr) * (1 + 1e-12);
  }
  return *std::max_element(cL, cL + k);
}

// The global bound from the children's ranges f and global bounds L.
inline double ricci_global_lipschitz(const RicciParams& m, const Interval* f, const double* L,
                                     size_t k) {
  Scratch<double> cL(k);
  for (size_t i = 0; i < k; ++i) cL[i] = flat_product(ricci_arg_slope(m, i, f[i]), L[i]);
  return ricci_combine(m, cL.data(), k);
}

// The bound over a box where the children lie in f with box bounds L: the partials' bounds
// (power_sum_partial_bound for q = n, min(1, (B.hi/g_i.lo)^(n+1)) for q = -n) against the c_i
// L_i, the derivative-free bound and the global one.
inline double ricci_lipschitz(const RicciParams& m, const Interval* f, const double* L, size_t k,
                              double global_L) {
  Scratch<Interval> G(k);
  Scratch<double> cL(k);
  for (size_t i = 0; i < k; ++i) {
    G[i] = ricci_arg_range(m, i, f[i]);
    cL[i] = flat_product(ricci_arg_slope(m, i, f[i]), L[i]);
  }
  const Interval B = ricci_range(m, G.data(), k);
  double s = 0;
  for (size_t i = 0; i < k; ++i) {
    double a;
    if (m.positive) {
      a = power_sum_partial_bound({std::max(0.0, G[i].lo), std::max(0.0, G[i].hi)}, B, m.n);
    } else {
      a = G[i].lo > 0 ? std::min(1.0, std::pow(B.hi / G[i].lo, m.n + 1) * (1 + 1e-13)) : 1;
    }
    s += flat_product(a, cL[i]);
  }
  return std::min({global_L, ricci_combine(m, cL.data(), k), s * (1 + 1e-12)});
}

// B's slope along a segment (docs/math.md §8, "Slopes along a segment") from the children's ranges
// f and slopes D there: each argument's slope by the chain rule (g = f: D; 1 - f: -D; 1/f: -D/f²
// with 1/f² between its ends' values, and 0 where f is at the floor), then the power mean's, which
// is the super-ellipsoidal intersection's for q = n and the union's for q = -n.
inline Interval ricci_slope(const RicciParams& m, const Interval* f, const Interval* D, size_t k) {
  Scratch<Interval> G(k), dG(k);
  for (size_t i = 0; i < k; ++i) {
    G[i] = ricci_arg_range(m, i, f[i]);
    switch (ricci_arg_kind(m, i)) {
      case RicciArg::Same:
        dG[i] = D[i];
        break;
      case RicciArg::SoftComplement:
        dG[i] = -D[i];
        break;
      case RicciArg::CgComplement: {
        if (f[i].hi <= kCgFloor) {
          dG[i] = 0.0;
          break;
        }
        const double lo = std::max(f[i].lo, kCgFloor);
        const Interval inv_sq(1 / (f[i].hi * f[i].hi) * (1 - 1e-12), 1 / (lo * lo) * (1 + 1e-12));
        dG[i] = -(D[i] * inv_sq);
        if (f[i].lo <= kCgFloor) dG[i] = hull(dG[i], 0.0);
        break;
      }
    }
  }
  const Interval B = ricci_range(m, G.data(), k);
  return m.positive ? super_intersection_slope(G.data(), dG.data(), k, m.n, B)
                    : super_union_slope(G.data(), dG.data(), k, m.n, B);
}

}  // namespace softtrace

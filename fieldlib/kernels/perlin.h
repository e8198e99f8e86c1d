// Perlin's set blends 1 - Π(1 - f_i), Π f_i, f_1 Π_{i>=2} (1 - f_i) — 002 Eqs. 4–6, docs/math.md
// §5.2: products of factors g_i = f_i or 1 - f_i, complemented for the union. The kernels are
// shared by the model node (blends_set.cpp) and the program's Perlin instruction, so both compute
// the same bits from the children's values, gradients, intervals and Lipschitz bounds.
#pragma once

#include <algorithm>

#include "math/bound_util.h"
#include "math/interval.h"
#include "math/scratch.h"
#include "math/vec.h"

namespace softtrace {

enum class PerlinMode { Union, Intersection, Difference };

// Whether child i's factor is 1 - f_i.
inline bool perlin_complemented(PerlinMode m, size_t i) {
  return m == PerlinMode::Union || (m == PerlinMode::Difference && i > 0);
}
inline Interval perlin_factor(PerlinMode m, size_t i, Interval f) {
  return perlin_complemented(m, i) ? Interval(1) - f : f;
}

// The blend of the children's values f (overwritten by the factors g_i) and, when grad is
// non-null, its gradient from the children's gradients gg (overwritten by ∇g_i).
inline double perlin(PerlinMode mode, double* g, Vec3* gg, size_t k, Vec3* grad) {
  for (size_t i = 0; i < k; ++i)
    if (perlin_complemented(mode, i)) {
      g[i] = 1 - g[i];
      if (grad) gg[i] = -gg[i];
    }
  // Prefix and suffix products give Π_{j≠i} g_j without dividing by a g_i that may be 0.
  Scratch<double, 17> pre(k + 1), suf(k + 1);  // 16 children on the stack, as g
  pre[0] = suf[k] = 1.0;
  for (size_t i = 0; i < k; ++i) pre[i + 1] = pre[i] * g[i];
  for (size_t i = k; i-- > 0;) suf[i] = suf[i + 1] * g[i];
  const double sign = mode == PerlinMode::Union ? -1 : 1;
  if (grad) {
    *grad = {};
    for (size_t i = 0; i < k; ++i) *grad += gg[i] * (sign * pre[i] * suf[i + 1]);
  }
  return mode == PerlinMode::Union ? 1 - pre[k] : pre[k];
}

// Interval arithmetic on the product of the factors (sound for any range).
inline Interval perlin_interval(PerlinMode mode, const Interval* f, size_t k) {
  Interval prod(1);
  for (size_t i = 0; i < k; ++i) prod = prod * perlin_factor(mode, i, f[i]);
  return mode == PerlinMode::Union ? Interval(1) - prod : prod;
}

// Σ_i L_i sup|Π_{j≠i} G_j| over the factors' ranges G ([PE-3]).
inline double perlin_slope(const Interval* G, const double* L, size_t k) {
  double s = 0;
  for (size_t i = 0; i < k; ++i) {
    double m = 1;  // a zero factor wins over an infinite one (inf * 0 would be NaN)
    for (size_t j = 0; j < k && m != 0; ++j)
      if (j != i) m = flat_product(m, magnitude(G[j]));
    s += flat_product(m, L[i]);
  }
  return s * (1 + 1e-12);
}

// The bound over a box from the children's intervals f and box bounds L, capped by the global one.
inline double perlin_lipschitz(PerlinMode mode, const Interval* f, const double* L, size_t k,
                               double global_L) {
  Scratch<Interval> G(k);
  for (size_t i = 0; i < k; ++i) G[i] = perlin_factor(mode, i, f[i]);
  return std::min(global_L, perlin_slope(G.data(), L, k));
}

// d B(f_1(t), ..., f_k(t))/dt from the children's ranges f and slope enclosures D along a segment
// (docs/math.md §8, "Slopes along a segment"): the product rule, (Π g_j)' = Σ_i g_i' Π_{j≠i} g_j
// with g_i' = ±f_i', in interval arithmetic over the factors' ranges; the union's 1 - Π negates it.
inline Interval perlin_slope_along(PerlinMode mode, const Interval* f, const Interval* D,
                                   size_t k) {
  Scratch<Interval> G(k);
  for (size_t i = 0; i < k; ++i) G[i] = perlin_factor(mode, i, f[i]);
  Interval s(0);
  for (size_t i = 0; i < k; ++i) {
    Interval term = perlin_complemented(mode, i) ? -D[i] : D[i];
    for (size_t j = 0; j < k; ++j)
      if (j != i) term = term * G[j];
    s = s + term;
  }
  return mode == PerlinMode::Union ? -s : s;
}

}  // namespace softtrace

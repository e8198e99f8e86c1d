// Weighted power sums (Σ u_i^n)^(1/n), u_i >= 0: the building block of every LP-type distance
// function (docs/math.md §2.5–§2.10), with the derivative and bound facts of docs/math.md §8.
#pragma once

#include <cmath>

#include "math/interval.h"
#include "math/root_20.h"

namespace softtrace {

// s^(1/n) for s >= 0, a power sum's root: n = 1 none, n = 2, 4, 8 or 16 by one to four square
// roots (each correctly rounded, so within an ulp all told, as std::pow; the papers' bars and
// cylinders take n = 4 and 8), n = 20 (their cubes and bars) by root_20, other n by std::pow.
inline double power_root(double s, double n) {
  if (n == 2) return std::sqrt(s);
  if (n == 1) return s;
  if (n == 20) return root_20(s);
  if (n == 4) return std::sqrt(std::sqrt(s));
  if (n == 8) return std::sqrt(std::sqrt(std::sqrt(s)));
  if (n == 16) return std::sqrt(std::sqrt(std::sqrt(std::sqrt(s))));
  // A sum relative to its largest term is exactly 1 wherever the others' powers fall below half
  // an ulp of it (n = 20: every other term under 0.16 of the largest), and pow(1, y) is 1.
  if (s == 1) return 1;
  return std::pow(s, 1 / n);
}

// f = (Σ u_i^n)^(1/n), evaluated relative to the largest u_i so n = 20 neither overflows nor
// underflows. When dfdu is non-null it receives ∂f/∂u_i = (u_i/f)^(n-1) (0 where u_i = 0 and
// n < 1, and 0 at f = 0, both elements of the subdifferential by symmetry).
double power_sum(const double* u, int k, double n, double* dfdu);

// power_sum without the derivative over `lanes` points at once (structure of arrays: term i of
// lane l at u[i][l]) into f[l]; the same bits as power_sum lane by lane. lanes <= 16.
void power_sum_lanes(const double* const* u, int k, double n, int lanes, double* f);

// f is non-decreasing in every u_i, so its image over a box of u is [f(lo), f(hi)].
Interval power_sum(const Interval* u, int k, double n);

// Bound on ∂f/∂u_i = (u_i/f)^(n-1) where u_i ∈ ui and f ∈ f_range: at most 1 for n >= 1
// (u_i <= f); (f_hi/u_lo)^(1-n) for n < 1, infinite when u_i can reach 0.
double power_sum_partial_bound(Interval ui, Interval f_range, double n);

// The range of ∂f/∂u_i = (u_i/f)^(n-1) where u_i ∈ ui and f ∈ f_range, for n >= 1: between
// (u_lo/f_hi)^(n-1) and power_sum_partial_bound (both 1 for n = 1, where f = Σ u_i). n < 1: [0,
// inf].
Interval power_sum_partial(Interval ui, Interval f_range, double n);

// The range of df/dt along a path where u_i ∈ u[i] and du_i/dt ∈ du[i], f ∈ f_range: f is
// Lipschitz for n >= 1, so its difference quotients lie in Σ ∂f/∂u_i · du_i/dt over those ranges
// (the chain rule wherever f is differentiable, which is almost everywhere). Widened for the
// products' and the sum's rounding. Entire for n < 1 or where a rate is not finite.
Interval power_sum_slope(const Interval* u, const Interval* du, int k, Interval f_range, double n);
// power_sum_slope with each term's power_sum_partial_bound already computed (a Lipschitz bound over
// the same box computes them): the same interval without its pows again. partial_hi is read only
// for n > 1.
Interval power_sum_slope(const Interval* u, const Interval* du, int k, Interval f_range, double n,
                         const double* partial_hi);

// The global Lipschitz constant of g(v) = (Σ |w_i v_i|^n)^(1/n) over R^k (Euclidean): the
// l_q -> l_2 norm of diag(w) with 1/n + 1/q = 1, i.e. max_i w_i for n >= 2 and
// ||w||_r with r = 2n/(2-n) for 1 <= n < 2 (Hölder, attained). Infinite for n < 1 (docs/math.md
// §8).
double gauge_lipschitz(const double* w, int k, double n);

}  // namespace softtrace

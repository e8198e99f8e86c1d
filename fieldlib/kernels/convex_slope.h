// The slope of a convex gauge along a segment from the gradients at its two ends (docs/math.md §8,
// "Slopes along a segment"): the L^p metric for n >= 2 and the spherical product for n1, n2 >= 2
// are convex (a monotone norm of convex one-sided terms), so along a line their derivative never
// falls and the ends' one-sided derivatives bound it, as for the segment and the torus
// (skeletal.h). Two point gradients cost less than the chain rule over the box's partial ranges
// (power_sum_slope) and give the exact range instead of a hull.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "kernels/gauge.h"
#include "math/int_power.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// f = (Σ u_i^n)^(1/n), u_i >= 0, n >= 2, returned, and ∂f/∂u_i into partial[i]: with m the
// largest u_i, b_i = u_i/m and s = Σ b_i^n, ∂f/∂u_i = (u_i/f)^(n-1) = b_i^(n-1) s^(1/n)/s, so one
// power of each b_i serves both the sum and the partials (power_sum with its partials takes two).
// Within a few ulps per term for the integer exponents, by squaring; 0 partials at f = 0 (the
// subgradient 0).
// power_sum_partials with the power b^(n-1) and the root s^(1/n) as given.
template <class PowN1, class Root>
double power_sum_partials_with(const double* u, int k, double* partial, const PowN1& pow_n1,
                               const Root& root_n) {
  double m = 0;
  for (int i = 0; i < k; ++i) m = std::max(m, u[i]);
  if (!(m > 0)) {
    std::fill(partial, partial + k, 0.0);
    return m;
  }
  double s = 0;
  for (int i = 0; i < k; ++i) {
    const double b = u[i] / m;
    const double p = pow_n1(b);
    s += p * b;
    partial[i] = p;
  }
  const double root = root_n(s), scale = root / s;
  for (int i = 0; i < k; ++i) partial[i] *= scale;
  return m * root;
}

inline double power_sum_partials(const double* u, int k, double n, double* partial) {
  // The papers' cubes and bars (n = 20) with the exponent known at compile time: the same
  // multiplications without a test of n per term, and power_root's n = 20 branch, root_20,
  // inline without its tests of n (the out-of-line call was 28.8 M of Fig. 12(b)'s instructions
  // at 640x480, 62 a root).
  if (n == 20)
    return power_sum_partials_with(
        u, k, partial, [](double b) { return pow_by_squaring<19>(b); },
        [](double s) { return root_20(s); });
  const bool squaring = n <= 65 && n == static_cast<int>(n);
  return power_sum_partials_with(
      u, k, partial,
      [&](double b) {
        return squaring ? pow_by_squaring(b, static_cast<int>(n) - 1) : std::pow(b, n - 1);
      },
      [n](double s) { return power_root(s, n); });
}

// The last segment's two ends of one gauge instruction, keyed by its constants' address: a ray's
// next segment starts where the last ended, and a halved piece shares an end with its parent, so
// an end's f and gradient (a function of the point alone: the same bits found or computed) are
// often known. A small table in the workspace, indexed by the instruction's place in its program.
// Four points, the newest written over the oldest: after a halving, the piece's far half ends
// where the whole did, two segments back.
struct GaugeEnds {
  static constexpr int kTable = 64, kPoints = 4;
  const double* key = nullptr;
  int next = 0;  // the slot the next new point takes
  Vec3 p[kPoints];
  double f[kPoints] = {0, 0, 0, 0};
  Vec3 g[kPoints];
  // The latest slope's segment ends, in order, and f there: written by a call that computed both,
  // cleared by one that did not. A consumer later in the same bounds pass (a radius transform's
  // d/f, RadiusTransformOp::ratio_along) reads this pass's values or none: whether the points
  // above still hold an end depends on the thread's earlier rays, and so would its bits.
  Vec3 last[2];
  double last_f[2] = {0, 0};
  bool last_valid = false;
};

// df/dt along [A, B] (t in [0, len], the world length), f convex, C^1 (n >= 2 makes the gauges so)
// with |∇f| <= L and ‖∇²f‖ <= hess / f: `kernel(p, &g)` gives f(p) and ∇f(p) (found in `ends`
// where the last segment of the same instruction, `key`, had that end). [∇f(A)·e, ∇f(B)·e] / len
// (e = B - A) holds every derivative in between; each end's is the exact one's to within
// 1e-9 |e| L (as ellipsoid_on_segment's), and the ends themselves are known only to within pad
// (plus the rounding of coordinates of their size), where the gradient may turn by hess / f_near
// times that distance, f_near the least f there. An end where f may be near 0 takes the
// subgradient's extreme, -|e| L or |e| L. Entire for a degenerate segment.
//
// With `range`, also f's range along the segment (within pad of it) from the same two ends, where
// both are finite (*range_written says whether): a convex f is largest at an end, and it lies
// above both ends' tangents, f(A) + lo s and f(B) - hi (1 - s) for s in [0, 1] ([lo, hi] the
// derivatives' bounds in units of e), so at least where they meet. A point within pad of the
// segment is within pad of a parallel one, on which the same bounds hold with ends L pad away.
// This replaces the two power sums over the segment's box (a root each) by what the slope
// computed, and is tighter: the box's corners are farther out than the segment.
//
// `kinks(p)`: a lower bound on the distance from p to the nearest point where f is not C^1 (the
// inner L^1 sum of a spherical product with n1 = 1, whose gradient jumps on planes). Only the
// pad needs smoothness: any subgradient at an exact end bounds a convex f's derivative, but a
// point within pad of an end must see the gradient turn by at most hess / f_near times that
// distance. An end within pad of a kink takes the subgradient's extreme. Smooth: none anywhere.
struct Smooth {
  double operator()(const Vec3&) const { return std::numeric_limits<double>::infinity(); }
};

template <class Kernel, class Kinks = Smooth>
Interval convex_slope_on_segment(const Kernel& kernel, GaugeEnds* ends, const double* key,
                                 const Vec3& A, const Vec3& B, double pad, double len, double L,
                                 double hess, Interval* range = nullptr,
                                 bool* range_written = nullptr, const Kinks& kinks = {}) {
  if (range_written) *range_written = false;
  if (ends && ends->key != key) {
    ends->key = key;
    ends->next = 0;
    for (Vec3& p : ends->p) p = {NAN, NAN, NAN};  // matches no point
  }
  if (ends) ends->last_valid = false;
  if (!(len > 0) || !std::isfinite(L)) return Interval::entire();
  const Vec3 e = B - A;
  const double ne = length(e), reach = ne * L;
  const double stray = pad + 1e-12 * std::max(max_abs(A), max_abs(B)) + 1e-300;
  double f[2];
  Vec3 g[2];
  const Vec3* P[2] = {&A, &B};
  for (int i = 0; i < 2; ++i) {
    const Vec3& p = *P[i];
    int j = 0;
    while (ends && j < GaugeEnds::kPoints &&
           !(ends->p[j].x == p.x && ends->p[j].y == p.y && ends->p[j].z == p.z))
      ++j;
    if (ends && j < GaugeEnds::kPoints) {
      f[i] = ends->f[j];
      g[i] = ends->g[j];
      continue;
    }
    f[i] = kernel(p, &g[i]);
    if (ends) {
      const int k = ends->next;
      ends->next = (k + 1) % GaugeEnds::kPoints;
      ends->p[k] = p;
      ends->f[k] = f[i];
      ends->g[k] = g[i];
    }
  }
  if (ends) {
    ends->last[0] = A;
    ends->last[1] = B;
    ends->last_f[0] = f[0];
    ends->last_f[1] = f[1];
    ends->last_valid = true;
  }
  const auto end = [&](int i, double extreme) {
    const double near = f[i] * (1 - 1e-12) - L * stray;
    if (!(near > 0) || !std::isfinite(f[i])) return extreme;
    if constexpr (!std::is_same_v<Kinks, Smooth>) {
      if (!(kinks(*P[i]) > stray)) return extreme;
    }
    return dot(g[i], e) + (extreme > 0 ? 1 : -1) * ne * (1e-9 * L + hess * stray / near);
  };
  const double lo = std::max(-reach, end(0, -reach)), hi = std::min(reach, end(1, reach));
  if (!(lo <= hi)) return Interval::entire();  // NaN, or a bound past the other (never exact)
  if (range && std::isfinite(f[0]) && std::isfinite(f[1]) && std::isfinite(reach)) {
    // The kernels' values are within a few ulps of f (1e-13 relative holds them, as power_sum's
    // interval), the few operations below within a few ulps of `mag`.
    const double a = f[0] * (1 - 1e-13), b = f[1] * (1 - 1e-13);
    double low;
    if (lo >= 0)
      low = std::max(a, b - hi);
    else if (hi <= 0)
      low = std::max(b, a + lo);
    else  // lo < 0 < hi: the tangents meet where both are (hi a - lo b + lo hi) / (hi - lo)
      low = (hi * a - lo * b + lo * hi) / (hi - lo);
    const double mag = f[0] + f[1] + std::abs(lo) + std::abs(hi);
    const double off = L * stray + 1e-12 * mag + 1e-300;
    *range = {std::max(0.0, low - off), std::max(f[0], f[1]) * (1 + 1e-13) + off};
    if (range_written) *range_written = true;
  }
  return {iv::down(lo / len), iv::up(hi / len)};
}

}  // namespace softtrace

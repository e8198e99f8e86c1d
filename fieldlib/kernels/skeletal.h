// Distances about a skeleton as kernels shared by the model nodes and the program's instructions,
// so both compute the same bits: the line segment's Euclidean distance over the radius
// (distances_skeletal.cpp, Op::LineSegment) and the torus, the LP gauge about a circle in the
// (ρ, z) plane (distances_polar.cpp, Op::Torus, whose bounds are derived above the node class).
#pragma once

#include <algorithm>
#include <cmath>

#include "kernels/gauge.h"
#include "kernels/one_sided.h"
#include "math/bound_util.h"
#include "math/box.h"

namespace softtrace {

struct LineSegmentParams {
  Vec3 a, ab;   // the segment is a + t·ab, t in [0, 1]
  double r;     // influential radius
  double len2;  // |ab|^2
};

// The point of the segment nearest p.
inline Vec3 line_segment_closest(const LineSegmentParams& m, const Vec3& p) {
  const double t = m.len2 > 0 ? std::clamp(dot(p - m.a, m.ab) / m.len2, 0.0, 1.0) : 0.0;
  return m.a + m.ab * t;
}

// |X - closest(X)|/r   — 000 Eq. 5, docs/math.md §2.8.
inline double line_segment_distance(const LineSegmentParams& m, const Vec3& p, Vec3* grad) {
  const Vec3 q = p - line_segment_closest(m, p);
  const double dist = length(q);
  if (grad) *grad = dist > 0 ? q / (dist * m.r) : Vec3{};
  return dist / m.r;
}

// The Hessian of |X - closest(X)|/r: the distance e has Hessian (I - n n^T - a a^T)/e beside the
// segment (a its unit axis, n = (X - closest)/e) and (I - n n^T)/e beyond an end (a sphere's);
// on the ends' planes the spherical side's (one-sided). False on the segment (e = 0).
inline bool line_segment_hessian(const LineSegmentParams& m, const Vec3& p, Mat3* H) {
  const double t = m.len2 > 0 ? dot(p - m.a, m.ab) / m.len2 : 0.0;
  const Vec3 q = p - line_segment_closest(m, p);
  const double e = length(q);
  if (!(e > 0)) return false;
  const Vec3 n = q / e;
  const bool beside = t > 0 && t < 1;
  const Vec3 a = beside ? m.ab / std::sqrt(m.len2) : Vec3{};
  const double s = 1 / (e * m.r);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H->r[i][j] = ((i == j ? 1.0 : 0.0) - n[i] * n[j] - a[i] * a[j]) * s;
  return true;
}

// The value interval over `b`: the distance to a set is 1-Lipschitz, so over a box it is within
// half a diagonal of the distance at the centre. (The Lipschitz bound is 1/r everywhere.)
inline Interval line_segment_interval(const LineSegmentParams& m, const Box& b) {
  const double c = length(b.center() - line_segment_closest(m, b.center())), h = 0.5 * b.diagonal();
  return iv::out(std::max(0.0, c - h) / m.r, (c + h) / m.r);
}

// The segment distance along the segment [A, B] (the register's, s in [0, 1], `len` long in the
// world, its computed points within `pad` of it), narrowing the box's range in *range:
// - the distance to a convex set is convex along a line, so its largest value is at an end (grown
//   by pad / r, the distance being 1/r-Lipschitz, and by the ends' rounding);
// - for the same reason its derivative q·e/|q| (q = X - closest(X), e = B - A) only grows with s,
//   so the ends' one-sided derivatives bound it; an end on the segment itself (q = 0), or so close
//   that the rounding of q (a few ulps of the coordinates) turns its direction by more than 1e-11,
//   takes -|e| or |e|, the subgradient's extreme. Widened by 1e-9 |e| as ellipsoid_on_segment.
inline void line_segment_on_segment(const LineSegmentParams& m, const Vec3& A, const Vec3& B,
                                    double pad, double len, Interval* range, Interval* slope) {
  const Vec3 q0 = A - line_segment_closest(m, A), q1 = B - line_segment_closest(m, B);
  const Vec3 e = B - A;
  const double n0 = length(q0), n1 = length(q1), ne = length(e);
  const double scale = std::max({max_abs(A), max_abs(B), max_abs(m.a), max_abs(m.a + m.ab)});
  const double hi = (std::max(n0, n1) + pad + 1e-12 * scale) / m.r * (1 + 1e-15);
  range->hi = std::min(range->hi, hi);
  if (!(len > 0)) {
    *slope = Interval::entire();
    return;
  }
  const double tiny = 1e-4 * scale;
  const double lo_end = n0 > tiny ? dot(q0, e) / n0 : -ne,
               hi_end = n1 > tiny ? dot(q1, e) / n1 : ne;
  const double spad = 1e-9 * ne + 1e-300;
  *slope = {std::max(-ne, lo_end - spad) / (m.r * len) * (1 + 1e-12),
            std::min(ne, hi_end + spad) / (m.r * len) * (1 + 1e-12)};
}

// ρ = |(x, y)| over a box: exact image by interval arithmetic.
inline Interval rho_range(const Box& b) {
  return sqrt(sqr(b.axis(0)) + sqr(b.axis(1)));
}

// ∇ρ = (x, y, 0)/ρ; 0 on the axis (an element of the subdifferential, the unit disc).
inline Vec3 rho_gradient(const Vec3& p, double rho) {
  return rho > 0 ? Vec3{p.x / rho, p.y / rho, 0} : Vec3{};
}

struct TorusParams {
  double R, a, b, n, global_L;  // major radius, radii in ρ and z, exponent, gauge_lipschitz
};

// ((|ρ - R|/a)^n + (|z|/b)^n)^(1/n)   — docs/scene-format.md torus, docs/math.md §2.1, §2.5.
inline double torus(const TorusParams& m, const Vec3& p, Vec3* grad) {
  const double rho = std::hypot(p.x, p.y), s = rho - m.R;
  const double u[2] = {std::abs(s) / m.a, std::abs(p.z) / m.b};
  double d[2];
  const double f = power_sum(u, 2, m.n, grad ? d : nullptr);
  if (grad) {
    *grad = rho_gradient(p, rho) * (d[0] * sgn(s) / m.a);
    grad->z = d[1] * sgn(p.z) / m.b;
  }
  return f;
}

// The rate of ρ along the segment [A, B] per unit of s ∈ [0, 1]: ρ, the distance to the z axis, is
// convex along a line, so ρ' = (X·e)_xy / ρ only grows with s and the ends bound it; an end on the
// axis, or so near it that the rounding of its coordinates turns (x, y)/ρ by more than 1e-11, takes
// -|e_xy| or |e_xy|, the subgradient's extreme. Widened by 1e-9 |e_xy| as ellipsoid_on_segment.
inline Interval rho_rate_on_segment(const Vec3& A, const Vec3& B) {
  const double ex = B.x - A.x, ey = B.y - A.y, ne = std::hypot(ex, ey);
  const double rA = std::hypot(A.x, A.y), rB = std::hypot(B.x, B.y);
  const double tiny = 1e-4 * std::max(max_abs(A), max_abs(B));
  const double lo = rA > tiny ? (A.x * ex + A.y * ey) / rA : -ne;
  const double hi = rB > tiny ? (B.x * ex + B.y * ey) / rB : ne;
  const double pad = 1e-9 * ne + 1e-300;
  return {std::max(-ne, lo - pad), std::min(ne, hi + pad)};
}

// The value interval and the Lipschitz bound over `b` from one computation of the terms: ∇f has
// the orthogonal parts ∂_1/a (along ∇ρ) and ∂_2/b (along z), each bounded from the intervals.
// torus_bounds_along with `seg` (the segment [seg[0], seg[1]] inside b, `len` long in the world)
// also the slope along it: the chain rule through |ρ - R|/a and |z|/b (OneSidedTerm::rate, each
// piecewise linear in its argument) into the power sum's partials (power_sum_slope), per unit of
// the world's t.
inline void torus_bounds_along(const TorusParams& m, const Box& b, Interval* value,
                               double* lipschitz, const Vec3* seg, double len, Interval* slope) {
  const Interval s = rho_range(b) - Interval(m.R), z = b.axis(2);
  const Interval u[2] = {divided(abs(s), m.a), divided(abs(z), m.b)};
  const Interval f = power_sum(u, 2, m.n);
  *value = f;
  if (!lipschitz) return;
  const double g1 = power_sum_partial_bound(u[0], f, m.n) / m.a;
  const double g2 = power_sum_partial_bound(u[1], f, m.n) / m.b;
  const double L = std::sqrt(g1 * g1 + g2 * g2) * (1 + 1e-13);
  *lipschitz = std::isnan(L) ? m.global_L : std::min(m.global_L, L);
  if (!seg) return;
  if (!(len > 0)) {
    *slope = Interval::entire();
    return;
  }
  const double ez = seg[1].z - seg[0].z, zpad = 1e-9 * std::abs(ez) + 1e-300;
  const Interval inv_len = Interval(1.0) / Interval(len);
  const Interval du[2] = {
      OneSidedTerm{m.a, m.a, 0}.rate(s, rho_rate_on_segment(seg[0], seg[1]) * inv_len),
      OneSidedTerm{m.b, m.b, 0}.rate(z, Interval(ez - zpad, ez + zpad) * inv_len)};
  *slope = power_sum_slope(u, du, 2, f, m.n);
}

// Over the box only.
inline void torus_bounds(const TorusParams& m, const Box& b, Interval* value, double* lipschitz) {
  torus_bounds_along(m, b, value, lipschitz, nullptr, 0, nullptr);
}

}  // namespace softtrace

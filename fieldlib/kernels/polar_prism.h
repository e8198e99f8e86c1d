// The polar prism (h^n + |z/c|^n)^(1/n), h = ρ/R(φ), whose cross-section radius
// R(φ) = r0 (1 + A g(kφ)) is docs/math.md §10.1's rose or star (the substitutes for [000] Fig. 13's
// rose bar and star contour), as kernels shared by the model node (distances_polar.cpp) and the
// program's PolarPrism instruction, so both compute the same bits. Ray-linear about the origin.
//
// Bounds: in polar coordinates ∇h = e_ρ/R - (R'(φ)/R²) e_φ (∂h/∂φ / ρ, ρ cancels), so
// |∇h|² = (R² + R'²)/R⁴; h is continuous and piecewise smooth (the star's kinks), so the largest
// |∇h| over the R range a box reaches bounds its slope there. ∇h ⟂ z, so the outer gauge composes
// as for the superquadric (gauge_lipschitz / partial bounds).
// - star: |R'| = r0 A k (2/π) everywhere, so |∇h|² = 1/R² + R'²/R⁴ is largest at the smallest R.
// - rose: with q = R/r0 = 1 + A cos θ, R'² = r0² k² (A² - (q-1)²), and with s = 1/q
//   r0² |∇h|² = P(s) = (1-k²) s² + 2k² s³ + k² (A²-1) s⁴, a quartic maximised over the s range at
//   its ends or where P'(s)/(2s) = (1-k²) + 3k² s + 2k² (A²-1) s² vanishes.
// Over a box whose (x, y) rectangle misses the axis, the φ range comes from the corners (the
// span is below π), which gives R's range; elsewhere R ∈ [r0 (1-A), r0 (1+A)].
#pragma once

#include <algorithm>
#include <cmath>

#include "kernels/gauge.h"
#include "kernels/one_sided.h"
#include "kernels/skeletal.h"
#include "math/bound_util.h"
#include "math/box.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// The angular profile g(θ) ∈ [-1, 1] of R(φ) = r0 (1 + A g(kφ)): cos θ (rose) or the triangle
// wave (2/π) asin(cos θ) = 1 - 2|θ|/π for θ wrapped to [-π, π] (star). Both have their maxima at
// θ ∈ 2πZ, minima at θ ∈ π + 2πZ, and are monotone in between. |g'| <= 1 and 2/π respectively.
enum class PolarProfile { Cosine, Triangle };

inline double polar_profile(PolarProfile kind, double theta, double* dg) {
  if (kind == PolarProfile::Cosine) {
    if (dg) *dg = -std::sin(theta);
    return std::cos(theta);
  }
  const double w = std::remainder(theta, 2 * M_PI);
  if (dg) *dg = -2 / M_PI * sgn(w);
  return 1 - 2 * std::abs(w) / M_PI;
}

struct PolarPrismParams {
  double r0, k, A;  // R(φ) = r0 (1 + A g(kφ)); k, the lobes, is an integer
  PolarProfile kind;
  double c, n;            // half-height and exponent
  double dR_max, global;  // max |R'(φ)| and the global Lipschitz bound
};

// The largest |∇h| for R ∈ R_range (see the file comment).
inline double polar_prism_h_slope(const PolarPrismParams& m, Interval R_range) {
  const double R_lo = R_range.lo;
  if (m.kind == PolarProfile::Triangle || m.A == 0)
    return std::sqrt(1 / (R_lo * R_lo) + std::pow(m.dR_max / (R_lo * R_lo), 2)) * (1 + 1e-13);
  const double k2 = m.k * m.k, c4 = k2 * (m.A * m.A - 1);
  const double s_lo = m.r0 / R_range.hi, s_hi = m.r0 / R_lo;
  double best = 0;
  auto consider = [&](double s) {
    if (!(s >= s_lo && s <= s_hi)) return;
    const double s2 = s * s;
    const double P = (1 - k2) * s2 + 2 * k2 * s2 * s + c4 * s2 * s2;
    const double M = std::abs(1 - k2) * s2 + 2 * k2 * s2 * s + std::abs(c4) * s2 * s2;
    best = std::max(best, P + 1e-12 * M);  // M bounds the terms, so covers their rounding
  };
  consider(s_lo);
  consider(s_hi);
  // Roots of 2 c4 s² + 3 k² s + (1 - k²) = 0 (c4 < 0 since A < 1).
  const double disc = 9 * k2 * k2 - 8 * c4 * (1 - k2);
  if (disc >= 0) {
    const double r = std::sqrt(disc);
    consider((-3 * k2 + r) / (4 * c4));
    consider((-3 * k2 - r) / (4 * c4));
  }
  return std::sqrt(best) / m.r0 * (1 + 1e-12);
}

// The parameters for r0, k lobes, A, the profile, c and n: R's largest slope and the global bound,
// from the whole R range.
inline PolarPrismParams polar_prism_params(double r0, int k, double A, PolarProfile kind, double c,
                                           double n) {
  PolarPrismParams m{r0, double(k), A, kind, c, n, 0, 0};
  m.dR_max = r0 * A * k * (kind == PolarProfile::Cosine ? 1.0 : 2 / M_PI);
  const double wm[2] = {polar_prism_h_slope(m, {r0 * (1 - A), r0 * (1 + A)}), 1 / c};
  m.global = gauge_lipschitz(wm, 2, n);
  return m;
}

// R(φ) at (x, y), and g'(kφ) into *dg when non-null.
inline double polar_prism_radius(const PolarPrismParams& m, double x, double y, double* dg) {
  return m.r0 * (1 + m.A * polar_profile(m.kind, m.k * std::atan2(y, x), dg));
}

// f(p), and ∇f into *grad when non-null.
inline double polar_prism(const PolarPrismParams& m, const Vec3& p, Vec3* grad) {
  const double rho = std::hypot(p.x, p.y);
  double dg = 0;
  const double R = polar_prism_radius(m, p.x, p.y, grad ? &dg : nullptr);
  const double u[2] = {rho / R, std::abs(p.z) / m.c};
  double d[2];
  const double f = power_sum(u, 2, m.n, grad ? d : nullptr);
  if (grad) {
    Vec3 gh;
    if (rho > 0) {
      const double dR = m.r0 * m.A * m.k * dg;  // R'(φ)
      const Vec3 e_rho{p.x / rho, p.y / rho, 0}, e_phi{-p.y / rho, p.x / rho, 0};
      gh = e_rho / R - e_phi * (dR / (R * R));
    }
    *grad = gh * d[0];
    grad->z = d[1] * sgn(p.z) / m.c;
  }
  return f;
}

// The image of g over [t0, t1]: the end values, plus 1 or -1 where a maximum or minimum lies
// inside; widened by 1e-12 for the evaluation's rounding.
inline Interval polar_prism_profile_range(PolarProfile kind, double t0, double t1) {
  if (t1 - t0 >= 2 * M_PI) return {-1, 1};
  const double g0 = polar_profile(kind, t0, nullptr), g1 = polar_profile(kind, t1, nullptr);
  double lo = std::min(g0, g1), hi = std::max(g0, g1);
  if (std::ceil(t0 / (2 * M_PI)) * 2 * M_PI <= t1) hi = 1;
  if (std::ceil((t0 - M_PI) / (2 * M_PI)) * 2 * M_PI + M_PI <= t1) lo = -1;
  return {std::max(-1.0, lo - 1e-12), std::min(1.0, hi + 1e-12)};
}

// The range of kφ over the box, padded for atan2's rounding, into [*t0, *t1]; false where the
// (x, y) rectangle meets the axis (or is unbounded), where φ takes every value.
inline bool polar_prism_theta_range(const PolarPrismParams& m, const Box& b, double* t0,
                                    double* t1) {
  const bool misses_axis = b.lo.x > 0 || b.hi.x < 0 || b.lo.y > 0 || b.hi.y < 0;
  if (!misses_axis || !b.bounded()) return false;
  const Vec3 c = b.center();
  const double phi_c = std::atan2(c.y, c.x);
  double lo = 0, hi = 0;
  for (int i = 0; i < 4; ++i) {
    const double x = (i & 1) ? b.hi.x : b.lo.x, y = (i & 2) ? b.hi.y : b.lo.y;
    const double d = std::remainder(std::atan2(y, x) - phi_c, 2 * M_PI);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  const double pad = 1e-12 * (1 + std::abs(phi_c));  // atan2 and the subtraction's rounding
  *t0 = m.k * (phi_c + lo - pad);
  *t1 = m.k * (phi_c + hi + pad);
  return true;
}

// R(φ) over the box: [Rmin, Rmax] unless the rectangle misses the axis.
inline Interval polar_prism_radius_range(const PolarPrismParams& m, const Box& b) {
  Interval g(-1, 1);
  double t0, t1;
  if (polar_prism_theta_range(m, b, &t0, &t1)) g = polar_prism_profile_range(m.kind, t0, t1);
  return {iv::down(m.r0 * (1 + m.A * g.lo) * (1 - 1e-15)),
          iv::up(m.r0 * (1 + m.A * g.hi) * (1 + 1e-15))};
}

// R'(φ) = r0 A k g'(kφ) over the box: g' = -sin θ = cos(θ + π/2) for the rose, and for the star
// -2/π sgn(θ) (θ wrapped to [-π, π]), one-signed between multiples of π. The whole
// [-dR_max, dR_max] where φ takes every value.
inline Interval polar_prism_radius_rate(const PolarPrismParams& m, const Box& b) {
  double t0, t1;
  if (!polar_prism_theta_range(m, b, &t0, &t1)) return {-m.dR_max, m.dR_max};
  Interval dg(-1, 1);
  if (m.kind == PolarProfile::Cosine) {
    dg = polar_prism_profile_range(PolarProfile::Cosine, t0 + M_PI / 2, t1 + M_PI / 2);
  } else if (std::floor(t0 / M_PI) == std::floor(t1 / M_PI)) {
    dg = std::remainder(0.5 * (t0 + t1), 2 * M_PI) > 0 ? Interval(-1) : Interval(1);
  }
  const double scale = m.dR_max * (1 + 1e-12);
  return {dg.lo * scale, dg.hi * scale};
}

// The value interval and the Lipschitz bound over `b` (when lipschitz is non-null); with `seg`
// (the segment [seg[0], seg[1]] inside b, `len` long in the world) also the slope along it, per
// unit of the world's t. Along the line X = A + s e, h = ρ/R(φ) changes at
//   h' = ρ'/R - (ρ φ') R'(φ)/R²,  ρ φ' = (x e_y - y e_x)/ρ = L_z/ρ,  L_z = A_x e_y - A_y e_x,
// L_z being constant along a line (X × e = A × e); ρ' is bounded by its ends (ρ convex along a
// line, rho_rate_on_segment), ρ, R and R' by their ranges over the box. |z|/c changes at ±e_z/c
// (OneSidedTerm::rate); the power sum's partials chain them (power_sum_slope).
inline void polar_prism_bounds_along(const PolarPrismParams& m, const Box& b, Interval* value,
                                     double* lipschitz, const Vec3* seg, double len,
                                     Interval* slope) {
  const Interval rho = rho_range(b), R = polar_prism_radius_range(m, b), z = b.axis(2);
  const Interval u[2] = {rho / R, divided(abs(z), m.c)};
  const Interval f = power_sum(u, 2, m.n);
  *value = f;
  if (!lipschitz) return;
  const double g1 = power_sum_partial_bound(u[0], f, m.n) * polar_prism_h_slope(m, R);
  const double g2 = power_sum_partial_bound(u[1], f, m.n) / m.c;
  const double L = std::sqrt(g1 * g1 + g2 * g2) * (1 + 1e-13);
  *lipschitz = std::isnan(L) ? m.global : std::min(m.global, L);
  if (!seg) return;
  if (!(len > 0)) {
    *slope = Interval::entire();
    return;
  }
  const Vec3 A = seg[0], e = seg[1] - seg[0];
  const double lz = A.x * e.y - A.y * e.x;
  const double lz_pad = 1e-12 * (std::abs(A.x * e.y) + std::abs(A.y * e.x)) + 1e-300;
  const Interval Lz(lz - lz_pad, lz + lz_pad);
  const Interval dh =
      rho_rate_on_segment(seg[0], seg[1]) / R - Lz * polar_prism_radius_rate(m, b) / (rho * sqr(R));
  const double zpad = 1e-9 * std::abs(e.z) + 1e-300;
  const Interval inv_len = Interval(1.0) / Interval(len);
  const Interval du[2] = {
      dh * inv_len, OneSidedTerm{m.c, m.c, 0}.rate(z, Interval(e.z - zpad, e.z + zpad) * inv_len)};
  *slope = power_sum_slope(u, du, 2, f, m.n);
}

// Over the box only.
inline void polar_prism_bounds(const PolarPrismParams& m, const Box& b, Interval* value,
                               double* lipschitz) {
  polar_prism_bounds_along(m, b, value, lipschitz, nullptr, 0, nullptr);
}

}  // namespace softtrace

// The axis-aligned gauges: the L^p metric (000 Eq. 3; ellipsoids at n = 2) and the spherical
// product of one-sided terms (000 Eq. 8), both distances of a point register.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/convex_slope.h"
#include "kernels/gauge.h"
#include "kernels/lp_metric.h"
#include "kernels/spherical_product.h"
#include "program/ops/op_io.h"

namespace softtrace {

// The ellipsoidal distance d = |q|, q = p / a, along the segment [A, B] of length `len`, with q(s)
// = q0 + s qe for s in [0, 1]:
// - its range (grown by pad): d^2 is a quadratic in s, least at its vertex or an end;
// - the range of dd/dt (t = s len): q · qe / (|q| len) is |qe| cos(angle between q and qe) / len,
//   and that angle only shrinks as s grows, so the ends bound it (where q passes through 0, d has
//   a kink and that end's value is -|qe| or |qe|);
// - the first s where d may be below 1 (the support's entry): the nearer root of |q(s)|^2 = r^2,
//   r = 1 plus the range's growth, so that no computed point before it has d < 1.
// The ends' lengths serve all three. Reciprocals and the few operations err by a few ulps, far
// inside the 1e-12 (range) and 1e-9 (slope, entry) widening.
inline void ellipsoid_on_segment(const Vec3& a, const Vec3& ia, const Vec3& A, const Vec3& B,
                                 double pad, double len, Interval* range, Interval* slope,
                                 double* entry) {
  const Vec3 q0{A.x * ia.x, A.y * ia.y, A.z * ia.z}, q1{B.x * ia.x, B.y * ia.y, B.z * ia.z};
  // From B - A, not q1 - q0: a short segment far out must not lose its direction to cancellation.
  const Vec3 qe{(B.x - A.x) * ia.x, (B.y - A.y) * ia.y, (B.z - A.z) * ia.z};
  const double ee = dot(qe, qe), n0 = length(q0), n1 = length(q1);
  const double s = ee > 0 ? std::clamp(-dot(q0, qe) / ee, 0.0, 1.0) : 0.0;
  const double near = length(q0 + qe * s), far = std::max(n0, n1);
  // The vertex's s carries the ends' rounding (eps |q0| / |qe|): at most eps far off in d.
  const double grow = pad / std::min({a.x, a.y, a.z}) + 1e-12 * far;
  *range = {std::max(0.0, widen_down(near - grow, 1e-12)), widen_up(far + grow, 1e-12)};
  // |q0 + s qe|^2 = r^2: ee s^2 + 2 B s + c = 0 with c > 0 (the start is outside); the nearer
  // root c / (-B + sqrt(B^2 - ee c)) has no cancellation.
  const double r = widen_up(1 + grow, 1e-12), B0 = dot(q0, qe), c = (n0 - r) * (n0 + r);
  const double disc = B0 * B0 - ee * c;
  if (!(c > 0))
    *entry = 0;
  else if (B0 >= 0 || disc < 0)
    *entry = 1;  // moving away from the centre, or passing outside the support
  else
    *entry = std::min(1.0, c / (-B0 + std::sqrt(disc)) * (1 - 1e-9));
  if (!(len > 0)) {
    *slope = Interval::entire();
    return;
  }
  const double ne = std::sqrt(ee);
  const double lo = n0 > 0 ? dot(q0, qe) / n0 : -ne, hi = n1 > 0 ? dot(q1, qe) / n1 : ne;
  const double spad = 1e-9 * ne + kTiny;
  *slope = {std::max(-ne, lo - spad) / len * (1 + 1e-12),
            std::min(ne, hi + spad) / len * (1 + 1e-12)};
}

// slot out = lp_metric(reg in). Constants: LpMetricParams' own (a, n, global_L, 1/a).
struct LpMetricOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const LpMetricParams& m) { return m.constants(); }
  static LpMetricParams load(const double* c) { return LpMetricParams::load(c); }

  static void values(const Instr& in, const LaneIO& io) {
    const double* k = io.K + in.a;
    const LpMetricParams m = load(k);
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double* out = io.slot(in.out);
    const int n = io.n;
    if (m.n != 2) {
      // lp_metric's general path: the terms |p_i / a_i|, then the power sum over the lanes.
      double u[3][kBatch];
      for (int l = 0; l < n; ++l) {
        u[0][l] = std::abs(px[l] / k[0]);
        u[1][l] = std::abs(py[l] / k[1]);
        u[2][l] = std::abs(pz[l] / k[2]);
      }
      const double* rows[3] = {u[0], u[1], u[2]};
      power_sum_lanes(rows, 3, m.n, n, out);
      return;
    }
    // lp_metric's n = 2 path as a branch-free loop over the lanes (it vectorises), then the
    // kernel itself for the rare lanes outside its range.
    for (int l = 0; l < n; ++l) {
      const double x = px[l] / k[0], y = py[l] / k[1], z = pz[l] / k[2];
      out[l] = x * x + y * y + z * z;
    }
    for (int l = 0; l < n; ++l)
      out[l] = out[l] > 1e-280 && out[l] < 1e280 ? std::sqrt(out[l])
                                                 : lp_metric(m, {px[l], py[l], pz[l]}, nullptr);
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = lp_metric(load(io.K + in.a), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const double* k = io.K + in.a;
    io.local(in, [&](const Vec3& q, Vec3* g) { return lp_metric(load(k), q, g); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const LpMetricParams m = load(io.K + in.a);
    if (io.segment && m.n == 2) {
      // Along a segment the ellipsoid's range and slope are exact; 1/min(a) bounds |∇d|.
      const Vec3* S = io.segs + 2 * in.in;
      ellipsoid_on_segment(m.a, m.ia, S[0], S[1], io.seg_pads[in.in], io.seg_length, &io.I[in.out],
                           &io.D[in.out], &io.Q[in.out]);
      io.L[in.out] = m.global_L;
    } else if (io.slopes && m.n >= 2) {
      // Convex and C^1 (‖∇²f‖ <= (n - 1) max(1/a_i)^2 / f): the ends' values and gradients bound
      // the range and the slope along the segment. The Lipschitz bound is the global one, as the
      // ellipsoid's: the slope bounds the tracer's steps here, and the partials' bounds over the
      // box (a power per term) tightened no decision (the same evaluations on fig000_14n).
      const Vec3* S = io.segs + 2 * in.in;
      const double ia = std::max({m.ia.x, m.ia.y, m.ia.z});
      const auto kernel = [&](const Vec3& p, Vec3* g) {
        // u_i = |p_i|/a_i, ∂f/∂p_i = ∂f/∂u_i sgn(p_i) / a_i.
        const double u[3] = {std::abs(p.x) * m.ia.x, std::abs(p.y) * m.ia.y,
                             std::abs(p.z) * m.ia.z};
        double d[3];
        const double f = power_sum_partials(u, 3, m.n, d);
        *g = {d[0] * sgn(p.x) * m.ia.x, d[1] * sgn(p.y) * m.ia.y, d[2] * sgn(p.z) * m.ia.z};
        return f;
      };
      Interval range;
      bool along;
      io.D[in.out] = convex_slope_on_segment(kernel, io.ends_of(in), io.K + in.a, S[0], S[1],
                                             io.seg_pads[in.in], io.seg_length, m.global_L,
                                             (m.n - 1) * ia * ia, &range, &along);
      if (along) {
        io.I[in.out] = range;
        io.L[in.out] = m.global_L;
      } else {
        lp_metric_bounds(m, io.box(in.in), &io.I[in.out], &io.L[in.out]);
      }
      io.gauge_segment_facts(in.out);
    } else if (io.slopes) {
      Interval rate[3];
      io.axis_rates(in.in, rate);
      lp_metric_bounds(m, io.box(in.in), &io.I[in.out], &io.L[in.out], rate, &io.D[in.out]);
      io.gauge_segment_facts(in.out);
    } else {
      lp_metric_bounds(m, io.box(in.in), &io.I[in.out], &io.L[in.out]);
      io.segment_facts_from_box(in.out);
    }
  }
};

// slot out = spherical_product(reg in). Constants: r_pos, r_neg, dead for x, y, z in c[0..8],
// then n1, n2, global_L.
struct SphericalProductOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const SphericalProductParams& m) {
    const OneSidedTerm* t = m.t;
    return {t[0].r_pos, t[0].r_neg, t[0].dead, t[1].r_pos, t[1].r_neg, t[1].dead,
            t[2].r_pos, t[2].r_neg, t[2].dead, m.n1,       m.n2,       m.global_L};
  }
  static SphericalProductParams load(const double* c) {
    return {{{c[0], c[1], c[2]}, {c[3], c[4], c[5]}, {c[6], c[7], c[8]}}, c[9], c[10], c[11]};
  }

  static void values(const Instr& in, const LaneIO& io) {
    const SphericalProductParams m = load(io.K + in.a);
    const int n = io.n;
    // OneSidedTerm::value over the lanes as plain selects on locals, a loop GCC vectorises
    // (not with nested selects, nor with the parameters read through m): at most one of
    // s - L and -s - L is positive, so one quotient; 0/1 where neither is (NaN s included).
    double u[3][kBatch], h[kBatch];
    for (int i = 0; i < 3; ++i) {
      const double dead = m.t[i].dead, r_pos = m.t[i].r_pos, r_neg = m.t[i].r_neg;
      const double* s = io.reg(in.in, i);
      for (int l = 0; l < n; ++l) {
        const double a = s[l] - dead, b = -s[l] - dead;
        const double nb = b > 0 ? b : 0.0, rb = b > 0 ? r_neg : 1.0;
        u[i][l] = (a > 0 ? a : nb) / (a > 0 ? r_pos : rb);
      }
    }
    const double* inner[2] = {u[0], u[1]};
    power_sum_lanes(inner, 2, m.n1, n, h);
    const double* outer[2] = {h, u[2]};
    power_sum_lanes(outer, 2, m.n2, n, io.slot(in.out));
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = spherical_product(load(io.K + in.a), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(in,
             [&](const Vec3& q, Vec3* g) { return spherical_product(load(io.K + in.a), q, g); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const SphericalProductParams m = load(io.K + in.a);
    // n1 = 1 (Fig. 12's prism bar): h = u_x + u_y is convex too, and linear off the planes
    // |x| = dead_x, |y| = dead_y where its gradient jumps (the kinks, which the ends' pad must
    // not reach). There ∇²f = Jᵀ ∇²m J, J's rows ∇h and ∇u_z orthogonal with |∇h|² <= 2 max(1/r)²,
    // and ‖∇²m‖ <= (n2 - 1) / f (as the L^p metric's): ‖∇²f‖ <= 2 (n2 - 1) max(1/r)² / f. The
    // box's chain rule took two power sums with a root each, and their partials' powers.
    const bool l1 = m.n1 == 1;
    if (io.slopes && (m.n1 >= 2 || l1) && m.n2 >= 2) {
      // Convex and C^1 (‖∇²f‖ <= (n1 + n2 - 2) max(1/r)^2 / f over the terms' radii), or
      // piecewise so (n1 = 1, above): the ends' values and gradients bound the range and the
      // slope along the segment, and the Lipschitz bound is the global one (as the L^p metric's
      // above).
      const Vec3* S = io.segs + 2 * in.in;
      double ir = 0;
      for (const OneSidedTerm& t : m.t) ir = std::max(ir, t.slope());
      const double hess = (l1 ? 2 * (m.n2 - 1) : m.n1 + m.n2 - 2) * ir * ir;
      // n1 = 1: the distance to the planes where u_x + u_y kinks; n1 >= 2: C^1 everywhere.
      const auto kinks = [&](const Vec3& p) {
        return std::min(std::abs(std::abs(p.x) - m.t[0].dead),
                        std::abs(std::abs(p.y) - m.t[1].dead));
      };
      const auto kernel = [&](const Vec3& p, Vec3* g) {
        // h = (u_x^n1 + u_y^n1)^(1/n1), then m(h, u_z): the chain rule through both power sums.
        double dx, dy, dz, ph[2], pm[2];
        const double uh[2] = {m.t[0].value(p.x, &dx), m.t[1].value(p.y, &dy)};
        const double um[2] = {power_sum_partials(uh, 2, m.n1, ph), m.t[2].value(p.z, &dz)};
        const double f = power_sum_partials(um, 2, m.n2, pm);
        *g = {pm[0] * ph[0] * dx, pm[0] * ph[1] * dy, pm[1] * dz};
        return f;
      };
      Interval range;
      bool along;
      const auto slope = [&](const auto& kinks_of) {
        return convex_slope_on_segment(kernel, io.ends_of(in), io.K + in.a, S[0], S[1],
                                       io.seg_pads[in.in], io.seg_length, m.global_L, hess, &range,
                                       &along, kinks_of);
      };
      io.D[in.out] = l1 ? slope(kinks) : slope(Smooth{});
      if (along) {
        io.I[in.out] = range;
        io.L[in.out] = m.global_L;
      } else {
        spherical_product_bounds(m, io.box(in.in), &io.I[in.out], &io.L[in.out]);
      }
      io.gauge_segment_facts(in.out);
    } else if (io.slopes) {
      Interval rate[3];
      io.axis_rates(in.in, rate);
      spherical_product_bounds(m, io.box(in.in), &io.I[in.out], &io.L[in.out], rate, &io.D[in.out]);
      io.gauge_segment_facts(in.out);
    } else {
      spherical_product_bounds(m, io.box(in.in), &io.I[in.out], &io.L[in.out]);
      io.segment_facts_from_box(in.out);
    }
  }
};

}  // namespace softtrace

// The skeletal distances of a point register: the line segment (000 Eq. 5), the torus (an L^p
// gauge about a circle) and the polar prism (docs/math.md §10.1), bounded over the register's box.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/gauge.h"
#include "kernels/polar_prism.h"
#include "kernels/skeletal.h"
#include "program/ops/op_io.h"

namespace softtrace {

// slot out = |reg in - nearest point of the segment| / r. Constants: a in c[0..2], ab in c[3..5],
// then r and len2 = |ab|^2.
struct LineSegmentOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const LineSegmentParams& m) {
    return {m.a.x, m.a.y, m.a.z, m.ab.x, m.ab.y, m.ab.z, m.r, m.len2};
  }
  static LineSegmentParams load(const double* c) {
    return {{c[0], c[1], c[2]}, {c[3], c[4], c[5]}, c[6], c[7]};
  }

  // line_segment_distance over the lanes with the parameters in locals: the squared distances in
  // a loop GCC vectorises, then the roots (scalar: std::sqrt may set errno).
  static void values(const Instr& in, const LaneIO& io) {
    const LineSegmentParams m = load(io.K + in.a);
    const double ax = m.a.x, ay = m.a.y, az = m.a.z, bx = m.ab.x, by = m.ab.y, bz = m.ab.z;
    const double len2 = m.len2;
    const bool along = len2 > 0;
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double* out = io.slot(in.out);
    const int n = io.n;
    for (int l = 0; l < n; ++l) {
      const double w = (px[l] - ax) * bx + (py[l] - ay) * by + (pz[l] - az) * bz;
      const double t = along ? std::clamp(w / len2, 0.0, 1.0) : 0.0;
      const double qx = px[l] - (ax + bx * t), qy = py[l] - (ay + by * t),
                   qz = pz[l] - (az + bz * t);
      out[l] = qx * qx + qy * qy + qz * qz;
    }
    for (int l = 0; l < n; ++l) out[l] = std::sqrt(out[l]) / m.r;
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = line_segment_distance(load(io.K + in.a), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(
        in, [&](const Vec3& q, Vec3* g) { return line_segment_distance(load(io.K + in.a), q, g); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const LineSegmentParams m = load(io.K + in.a);
    io.I[in.out] = line_segment_interval(m, io.box(in.in));
    io.L[in.out] = 1 / m.r;
    if (!io.segment) {
      io.segment_facts_from_box(in.out);
      return;
    }
    const Vec3* S = io.segs + 2 * in.in;
    line_segment_on_segment(m, S[0], S[1], io.seg_pads[in.in], io.seg_length, &io.I[in.out],
                            &io.D[in.out]);
    io.gauge_segment_facts(in.out);
  }
};

// slot out = torus(reg in). Constants: R, a, b, n, global_L in c[0..4].
struct TorusOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const TorusParams& m) {
    return {m.R, m.a, m.b, m.n, m.global_L};
  }
  static TorusParams load(const double* c) { return {c[0], c[1], c[2], c[3], c[4]}; }

  // torus's terms lane by lane (hypot is a libm call), then power_sum_lanes.
  static void values(const Instr& in, const LaneIO& io) {
    const TorusParams m = load(io.K + in.a);
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double u[2][kBatch];
    for (int l = 0; l < io.n; ++l) {
      u[0][l] = std::abs(std::hypot(px[l], py[l]) - m.R) / m.a;
      u[1][l] = std::abs(pz[l]) / m.b;
    }
    const double* rows[2] = {u[0], u[1]};
    power_sum_lanes(rows, 2, m.n, io.n, io.slot(in.out));
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = torus(load(io.K + in.a), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(in, [&](const Vec3& q, Vec3* g) { return torus(load(io.K + in.a), q, g); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    if (!io.segment) {
      torus_bounds(load(io.K + in.a), io.box(in.in), &io.I[in.out], &io.L[in.out]);
      io.segment_facts_from_box(in.out);
      return;
    }
    torus_bounds_along(load(io.K + in.a), io.box(in.in), &io.I[in.out], &io.L[in.out],
                       io.segs + 2 * in.in, io.seg_length, &io.D[in.out]);
    io.gauge_segment_facts(in.out);
  }
};

// slot out = (h^n + |z/c|^n)^(1/n), h = rho/R(phi). Constants: r0, k, A, the profile (0 cosine, 1
// triangle), c, n, dR_max and the global bound in c[0..7].
struct PolarPrismOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const PolarPrismParams& m) {
    return {m.r0, m.k, m.A,      m.kind == PolarProfile::Cosine ? 0.0 : 1.0,
            m.c,  m.n, m.dR_max, m.global};
  }
  static PolarPrismParams load(const double* c) {
    return {c[0], c[1], c[2], c[3] == 0 ? PolarProfile::Cosine : PolarProfile::Triangle,
            c[4], c[5], c[6], c[7]};
  }

  // polar_prism's terms lane by lane (hypot, atan2 and the profile are libm calls), then
  // power_sum_lanes.
  static void values(const Instr& in, const LaneIO& io) {
    const PolarPrismParams m = load(io.K + in.a);
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double u[2][kBatch];
    for (int l = 0; l < io.n; ++l) {
      u[0][l] = std::hypot(px[l], py[l]) / polar_prism_radius(m, px[l], py[l], nullptr);
      u[1][l] = std::abs(pz[l]) / m.c;
    }
    const double* rows[2] = {u[0], u[1]};
    power_sum_lanes(rows, 2, m.n, io.n, io.slot(in.out));
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = polar_prism(load(io.K + in.a), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(in, [&](const Vec3& q, Vec3* g) { return polar_prism(load(io.K + in.a), q, g); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    if (!io.segment) {
      polar_prism_bounds(load(io.K + in.a), io.box(in.in), &io.I[in.out], &io.L[in.out]);
      io.segment_facts_from_box(in.out);
      return;
    }
    polar_prism_bounds_along(load(io.K + in.a), io.box(in.in), &io.I[in.out], &io.L[in.out],
                             io.segs + 2 * in.in, io.seg_length, &io.D[in.out]);
    io.gauge_segment_facts(in.out);
  }
};

}  // namespace softtrace

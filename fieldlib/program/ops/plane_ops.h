// The distances of planes: parallel planes |X·n|/a (000 Eq. 2), one branch [X·n]_+/a (002 f_o),
// and the generalized distance over k planes (000 Eq. 4), each a distance of a point register.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/gauge.h"
#include "kernels/generalized_distance.h"
#include "kernels/planes.h"
#include "math/scratch.h"
#include "program/ops/op_io.h"

namespace softtrace {

// The two one-plane distances, both = true for ParallelPlanes. Constants: n in c[0..2], then a.
template <bool both>
struct PlaneOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const PlaneParams& m) { return {m.n.x, m.n.y, m.n.z, m.a}; }
  static PlaneParams load(const double* c) { return {{c[0], c[1], c[2]}, c[3]}; }

  // The kernels' dot(p, n) and quotient over the lanes, with the parameters in locals (a loop GCC
  // vectorises); std::max keeps the kernel's answer for NaN and -0.
  static void values(const Instr& in, const LaneIO& io) {
    const double* K = io.K;
    const double nx = K[in.a], ny = K[in.a + 1], nz = K[in.a + 2], a = K[in.a + 3];
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double* out = io.slot(in.out);
    const int n = io.n;
    if (both) {
      for (int l = 0; l < n; ++l) out[l] = std::abs(px[l] * nx + py[l] * ny + pz[l] * nz) / a;
    } else {
      for (int l = 0; l < n; ++l) out[l] = std::max(px[l] * nx + py[l] * ny + pz[l] * nz, 0.0) / a;
    }
  }
  static double kernel(const PlaneParams& m, const Vec3& p, Vec3* g) {
    return both ? parallel_planes(m, p, g) : one_branch_plane(m, p, g);
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = kernel(load(io.K + in.a), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(in, [&](const Vec3& q, Vec3* g) { return kernel(load(io.K + in.a), q, g); });
  }
  // Over the register's box the kernel on the exact range of X·n; along a segment on its range
  // between the ends, with the slope below.
  static void bounds(const Instr& in, const BoundsIO& io) {
    const PlaneParams m = load(io.K + in.a);
    const Interval s = io.segment ? io.dot_on_segment(m.n, in.in) : dot_range(io.box(in.in), m.n);
    (both ? parallel_planes_bounds : one_branch_plane_bounds)(m, s, &io.I[in.out], &io.L[in.out]);
    io.D[in.out] = io.segment ? slope(m, s, in.in, io) : Interval(-io.L[in.out], io.L[in.out]);
    io.Q[in.out] = io.I[in.out].lo >= 1 ? 1 : 0;
  }

 private:
  // The slope along register r's segment, where X·n lies in `s`: X·n has the rate
  // rate_on_segment, so f's slope is ± that rate / a where X·n keeps its sign, and between the
  // two (|X·n|) or between it and 0 ([X·n]_+) where it may change sign. Capped by the bound 1/a.
  static Interval slope(const PlaneParams& m, Interval s, int r, const BoundsIO& io) {
    const double L = 1 / m.a;
    const Interval k = io.rate_on_segment(m.n, r);
    if (!(std::isfinite(k.lo) && std::isfinite(k.hi))) return {-L, L};  // a degenerate segment
    const Interval rate{std::max(-L, widen_down(k.lo / m.a, 1e-12)),
                        std::min(L, widen_up(k.hi / m.a, 1e-12))};
    if (both) {
      if (s.lo >= 0) return rate;
      if (s.hi <= 0) return -rate;
      const double most = std::max(-rate.lo, rate.hi);
      return {-most, most};
    }
    if (s.hi <= 0) return 0.0;
    return s.lo >= 0 ? rate : hull(rate, 0.0);
  }
};
using ParallelPlanesOp = PlaneOp<true>;
using OneBranchPlaneOp = PlaneOp<false>;

// slot out = generalized_distance(reg in), in.n normals. Constants: GeneralizedDistanceParams'
// layout (generalized_distance_constants), which the model node keeps as its own parameters.
struct GenDistanceOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static const std::vector<double>& constants(const std::vector<double>& c) { return c; }
  static GeneralizedDistanceParams load(const double* c, int k) { return {c, k}; }

  // The one-sided terms of X·n_i over the lanes as SphericalProduct's selects (a loop GCC
  // vectorises), one row per normal, then power_sum_lanes over the rows.
  static void values(const Instr& in, const LaneIO& io) {
    const GeneralizedDistanceParams m = load(io.K + in.a, in.n);
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    const int n = io.n;
    Scratch<double, 16 * kBatch> u(size_t(m.k) * kBatch);
    Scratch<const double*> rows(m.k);
    for (int i = 0; i < m.k; ++i) {
      const double* t = m.c + kGdHeader + kGdStride * i;
      const double nx = t[0], ny = t[1], nz = t[2], r_pos = t[3], r_neg = t[4], dead = t[5];
      double* ui = u.data() + i * kBatch;
      for (int l = 0; l < n; ++l) {
        const double s = px[l] * nx + py[l] * ny + pz[l] * nz;
        const double a = s - dead, b = -s - dead;
        const double nb = b > 0 ? b : 0.0, rb = b > 0 ? r_neg : 1.0;
        ui[l] = (a > 0 ? a : nb) / (a > 0 ? r_pos : rb);
      }
      rows[i] = ui;
    }
    power_sum_lanes(rows.data(), m.k, m.n(), n, io.slot(in.out));
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = generalized_distance(load(io.K + in.a, in.n), io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(in, [&](const Vec3& q, Vec3* g) {
      return generalized_distance(load(io.K + in.a, in.n), q, g);
    });
  }
  // The kernel on the ranges of X·n_i: over the register's box (the node's bits), or along the
  // segment, where X·n_i is affine, between its ends as for the planes.
  static void bounds(const Instr& in, const BoundsIO& io) {
    const GeneralizedDistanceParams m = load(io.K + in.a, in.n);
    Scratch<Interval> s(m.k), u(m.k);
    for (int i = 0; i < m.k; ++i)
      s[i] = io.segment ? io.dot_on_segment(m.normal(i), in.in)
                        : dot_range(io.box(in.in), m.normal(i));
    generalized_distance_bounds(m, s.data(), u.data(), &io.I[in.out], &io.L[in.out]);
    io.D[in.out] = io.slopes ? slope(m, s.data(), u.data(), io.I[in.out], io.L[in.out], in.in, io)
                             : Interval(-io.L[in.out], io.L[in.out]);
    io.Q[in.out] = io.I[in.out].lo >= 1 ? 1 : 0;
  }

 private:
  // The slope along register r's segment, where X·n_i lies in s[i], u_i in u[i] and f in `f`:
  // power_sum_slope over the terms, each u_i' the one-sided term's rate of X·n_i (its side of the
  // dead zone). Capped by the Lipschitz bound L.
  static Interval slope(const GeneralizedDistanceParams& m, const Interval* s, const Interval* u,
                        Interval f, double L, int r, const BoundsIO& io) {
    Scratch<Interval> du(m.k);
    for (int i = 0; i < m.k; ++i) du[i] = m.term(i).rate(s[i], io.rate_on_segment(m.normal(i), r));
    return BoundsIO::capped(power_sum_slope(u, du.data(), m.k, f, m.n()), L);
  }
};

}  // namespace softtrace

// The n-ary instructions: a group announcing children, the sum (soft_blend, 000 Eq. 12), min and
// max, and the combinations whose kernels take their children's values as arrays (the
// super-ellipsoidal union and intersection, 000 Eq. 6; Perlin's blends, 002 Eqs. 4-6; Ricci's,
// 002 Eq. 7; the scale method, 000 Eq. 8). Each reads its children's slots args[a..a+n); in the
// bounds pass, the kept children of the walk's group (BoundsIO::child), whose code the walk has
// already bounded.
//
// Rounding: a sum of k terms errs by at most (k-1)·2^-53·Σ|terms| (recursive summation); widened
// by k·2^-52·Σ|bounds| + 1e-300, the last also covering terms dropped as 0 that are subnormal.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/gauge.h"
#include "kernels/perlin.h"
#include "kernels/ricci.h"
#include "kernels/scale_operator.h"
#include "kernels/super_ellipsoidal.h"
#include "math/scratch.h"
#include "program/ops/op_io.h"

namespace softtrace {

// Announces the children of the n-ary instruction groups[a]. The evaluators' walks handle it
// (pruning chooses its children's ranges); as an operation it computes nothing.
struct GroupOp {
  static constexpr bool kPlaces = false;
  static constexpr bool kZeroWhenQuiet = false;
  // The children's register is read where the group starts (pruning's query).
  template <class Use, class Def>
  static void operands(Instr& in, const Program& p, const Use& use, const Def&) {
    int32_t reg = p.groups[in.a].reg;
    use(kReg, reg);
  }
  static void values(const Instr&, const LaneIO&) {}
  static void value(const Instr&, const PointIO&) {}
  static void gradient(const Instr&, const GradIO&) {}
  static void bounds(const Instr&, const BoundsIO&) {}
};

// slot out = Σ args. No constants.
struct SumOp : SlotsToSlot {
  static constexpr bool kZeroWhenQuiet = true;

  static void values(const Instr& in, const LaneIO& io) {
    double* out = io.slot(in.out);
    std::fill(out, out + io.n, 0.0);
    for (int j = 0; j < in.n; ++j) {
      const double* a = io.slot(io.args[in.a + j]);
      for (int l = 0; l < io.n; ++l) out[l] += a[l];
    }
  }
  static void value(const Instr& in, const PointIO& io) {
    double sum = 0;
    for (int j = 0; j < in.n; ++j) sum += io.S[io.args[in.a + j]];
    io.S[in.out] = sum;
  }
  static void gradient(const Instr& in, const GradIO& io) {
    Dual s{0, {}};
    for (int j = 0; j < in.n; ++j) {
      const Dual& a = io.S[io.args[in.a + j]];
      s.v += a.v;
      s.g += a.g;
    }
    io.S[in.out] = s;
  }
  // How far along the segment child c is exactly 0 (its quiet start where its result is a
  // field's: a distance's quiet start says nothing of 0). A template so that zero_when_quiet,
  // which needs every op's struct (ops.h), is looked up where the evaluator instantiates it.
  template <class IO>
  static double zero_start(const IO& io, const Group::Child& c) {
    return zero_when_quiet(io.program->code[c.end - 1].op) ? io.Q[c.slot] : 0.0;
  }
  template <class IO>
  static void bounds(const Instr& out, const IO& io) {
    Interval* I = io.I;
    double* L = io.L;
    const int n = out.n;
    double lo = 0, hi = 0, mag = 0, Ls = 0;
    for (int j = 0; j < n; ++j) {
      const int s = io.child(j).slot;
      lo += I[s].lo;
      hi += I[s].hi;
      mag += std::max(std::abs(I[s].lo), std::abs(I[s].hi));
      Ls += L[s];
    }
    const double pad = n * kEps * mag + kTiny;
    I[out.out] =
        std::isnan(lo) || std::isnan(hi) ? Interval::entire() : Interval(lo - pad, hi + pad);
    L[out.out] = Ls;
    if (!io.segment) return;  // slopes and quiet starts are the segments' (and scattered reads)
    // The derivative of a sum is the sum of the derivatives, rounded as the values are.
    double dlo = 0, dhi = 0, dmag = 0;
    for (int j = 0; j < n; ++j) {
      const Interval& d = io.D[io.child(j).slot];
      dlo += d.lo;
      dhi += d.hi;
      dmag += std::max(std::abs(d.lo), std::abs(d.hi));
    }
    const double dpad = n * kEps * dmag + kTiny;
    io.D[out.out] =
        std::isnan(dlo) || std::isnan(dhi) ? Interval::entire() : Interval(dlo - dpad, dhi + dpad);
    // The children dropped are 0 all along; the others until the first support entry.
    double quiet = 1;
    for (int j = 0; j < n; ++j) quiet = std::min(quiet, zero_start(io, io.child(j)));
    io.Q[out.out] = quiet;
  }
};

// slot out = min (is_min) or max of args; the first extreme in child order wins ties, as the
// model's min/max does. No constants.
template <bool is_min>
struct ExtremeOp : SlotsToSlot {
  static constexpr bool kZeroWhenQuiet = false;

  static void values(const Instr& in, const LaneIO& io) {
    double* out = io.slot(in.out);
    const double* a0 = io.slot(io.args[in.a]);
    std::copy(a0, a0 + io.n, out);
    for (int j = 1; j < in.n; ++j) {
      const double* a = io.slot(io.args[in.a + j]);
      for (int l = 0; l < io.n; ++l)
        if (is_min ? a[l] < out[l] : a[l] > out[l]) out[l] = a[l];
    }
  }
  static void value(const Instr& in, const PointIO& io) {
    double e = io.S[io.args[in.a]];
    for (int j = 1; j < in.n; ++j) {
      const double a = io.S[io.args[in.a + j]];
      if (is_min ? a < e : a > e) e = a;
    }
    io.S[in.out] = e;
  }
  static void gradient(const Instr& in, const GradIO& io) {
    Dual best = io.S[io.args[in.a]];
    for (int j = 1; j < in.n; ++j) {
      const Dual& a = io.S[io.args[in.a + j]];
      if (is_min ? a.v < best.v : a.v > best.v) best = a;
    }
    io.S[in.out] = best;
  }
  // min and max take some child's value at every point: their difference quotients lie in the
  // hull of the children's.
  static void bounds(const Instr& out, const BoundsIO& io) {
    const int n = out.n;
    Interval r = io.I[io.child(0).slot], D = io.D[io.child(0).slot];
    double Lm = 0;
    for (int j = 0; j < n; ++j) {
      const int s = io.child(j).slot;
      r = is_min ? min(r, io.I[s]) : max(r, io.I[s]);
      Lm = std::max(Lm, io.L[s]);
      D = hull(D, io.D[s]);
    }
    io.I[out.out] = r;
    io.L[out.out] = Lm;
    io.D[out.out] = D;
    io.Q[out.out] = 0;
  }
};
using MinOp = ExtremeOp<true>;
using MaxOp = ExtremeOp<false>;

// A combination whose kernel takes the children's values as an array: C::combine(in, K, x) on
// the values x[0..in.n) gathered, lane by lane (pow is a libm call); C::interval and
// C::lipschitz on the children's intervals and bounds (the model's bits). Along a segment the
// slope is C::slope's, the chain rule on the children's slopes where the kind derives one
// (docs/math.md §8, "Slopes along a segment"; capped by L), else the bound [-L, L]; and no quiet
// start (a combination of distances; 1 - Π(1 - f_i), the products and a soft Ricci union could
// claim one, not taken here).
template <class C>
struct Combination : SlotsToSlot {
  static constexpr bool kZeroWhenQuiet = false;

  static void values(const Instr& in, const LaneIO& io) {
    double* out = io.slot(in.out);
    Scratch<double> x(in.n);
    for (int l = 0; l < io.n; ++l) {
      for (int j = 0; j < in.n; ++j) x[j] = io.S[io.args[in.a + j] * kBatch + l];
      out[l] = C::combine(in, io.K, x.data());
    }
  }
  static void value(const Instr& in, const PointIO& io) {
    Scratch<double> x(in.n);
    for (int j = 0; j < in.n; ++j) x[j] = io.S[io.args[in.a + j]];
    io.S[in.out] = C::combine(in, io.K, x.data());
  }
  // The kernel on the children's values and gradients gathered.
  static void gradient(const Instr& in, const GradIO& io) {
    const size_t k = in.n;
    Scratch<double> x(k);
    Scratch<Vec3> g(k);
    io.gather(in, x.data(), g.data());
    Dual d;
    d.v = C::combine(in, io.K, x.data(), g.data(), &d.g);
    io.S[in.out] = d;
  }
  static void bounds(const Instr& out, const BoundsIO& io) {
    const int n = out.n;
    Scratch<Interval> x(n);
    Scratch<double> Lc(n);
    for (int j = 0; j < n; ++j) {
      const int s = io.child(j).slot;
      x[j] = io.I[s];
      Lc[j] = io.L[s];
    }
    double L;
    io.I[out.out] = C::interval(io.K + out.in, x.data(), Lc.data(), n, &L);
    io.L[out.out] = L;
    io.Q[out.out] = 0;
    if (!io.segment) {
      io.D[out.out] = {-L, L};
      return;
    }
    Scratch<Interval> D(n);
    for (int j = 0; j < n; ++j) D[j] = io.D[io.child(j).slot];
    io.D[out.out] = BoundsIO::capped(C::slope(io.K + out.in, x.data(), D.data(), n), L);
  }
  // No slope of its own: the Lipschitz bound's (capped above).
  static Interval slope(const double*, const Interval*, const Interval*, int) {
    return Interval::entire();
  }
};

// (Σ args^-n)^(-1/n), 000 Eq. 6 B_RU^cg. Constants (at in): n.
struct SuperUnionOp : Combination<SuperUnionOp> {
  static std::vector<double> constants(double n) { return {n}; }
  static double combine(const Instr& in, const double* K, const double* x) {
    return super_union(x, in.n, K[in.in]);
  }
  static double combine(const Instr& in, const double* K, const double* x, Vec3* g, Vec3* grad) {
    const double e = K[in.in];
    const double v = super_union(x, in.n, e);
    *grad = super_union_gradient(x, g, in.n, e, v);
    return v;
  }
  static Interval interval(const double* c, const Interval* x, const double* L, int n,
                           double* lipschitz) {
    const Interval f = super_union_interval(x, n, c[0]);
    *lipschitz = super_union_lipschitz(x, L, n, c[0], f);
    return f;
  }
  static Interval slope(const double* c, const Interval* x, const Interval* D, int n) {
    return super_union_slope(x, D, n, c[0], super_union_interval(x, n, c[0]));
  }
};

// (Σ [args]_+^n)^(1/n), B_RI^cg. Constants (at in): n, the global bound.
struct SuperIntersectOp : Combination<SuperIntersectOp> {
  static std::vector<double> constants(double n, double global_L) { return {n, global_L}; }
  static double combine(const Instr& in, const double* K, double* x) {
    return super_intersection(x, nullptr, in.n, K[in.in], nullptr);
  }
  static double combine(const Instr& in, const double* K, double* x, Vec3* g, Vec3* grad) {
    return super_intersection(x, g, in.n, K[in.in], grad);
  }
  static Interval interval(const double* c, const Interval* x, const double* L, int n,
                           double* lipschitz) {
    const Interval f = power_sum(x, n, c[0]);
    *lipschitz = super_intersection_lipschitz(x, L, n, c[0], f, c[1]);
    return f;
  }
  static Interval slope(const double* c, const Interval* x, const Interval* D, int n) {
    return super_intersection_slope(x, D, n, c[0], power_sum(x, n, c[0]));
  }
};

// Perlin's blends, 002 Eqs. 4-6. Constants (at in): the mode, the global bound.
struct PerlinOp : Combination<PerlinOp> {
  static std::vector<double> constants(PerlinMode mode, double global_L) {
    return {static_cast<double>(mode), global_L};
  }
  static PerlinMode load(const double* c) {
    return static_cast<PerlinMode>(static_cast<int>(c[0]));
  }
  static double combine(const Instr& in, const double* K, double* x) {
    return perlin(load(K + in.in), x, nullptr, in.n, nullptr);
  }
  static double combine(const Instr& in, const double* K, double* x, Vec3* g, Vec3* grad) {
    return perlin(load(K + in.in), x, g, in.n, grad);
  }
  static Interval interval(const double* c, const Interval* x, const double* L, int n,
                           double* lipschitz) {
    *lipschitz = perlin_lipschitz(load(c), x, L, n, c[1]);
    return perlin_interval(load(c), x, n);
  }
  static Interval slope(const double* c, const Interval* x, const Interval* D, int n) {
    return perlin_slope_along(load(c), x, D, n);
  }
};

// The scale method BSA2 / BSS2 of two children, 000 Eq. 8 (kernels/scale_operator.h). Constants
// (at in): the operator's own (ScaleOperator::constants).
struct ScaleOp : Combination<ScaleOp> {
  static std::vector<double> constants(const ScaleOperator& op) { return op.constants(); }
  static ScaleOperator load(const double* c) { return ScaleOperator::load(c); }
  // Combination's loop with the operator loaded once, not per lane.
  static void values(const Instr& in, const LaneIO& io) {
    const ScaleOperator op = load(io.K + in.in);
    const double *x1 = io.slot(io.args[in.a]), *x2 = io.slot(io.args[in.a + 1]);
    double* out = io.slot(in.out);
    for (int l = 0; l < io.n; ++l) out[l] = op(x1[l], x2[l], nullptr);
  }
  static double combine(const Instr& in, const double* K, const double* x) {
    return load(K + in.in)(x[0], x[1], nullptr);
  }
  static double combine(const Instr& in, const double* K, const double* x, Vec3* g, Vec3* grad) {
    double dh[2];
    const double h = load(K + in.in)(x[0], x[1], dh);
    *grad = g[0] * dh[0] + g[1] * dh[1];
    return h;
  }
  // One point: the two children read in place (Combination's gathers them into scratch).
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = load(io.K + in.in)(io.S[io.args[in.a]], io.S[io.args[in.a + 1]], nullptr);
  }
  // Not Combination's bounds: the two children read in place, the operator loaded once and its
  // sharp pick decided once for range and slope (nested scale unions walk one of these per level;
  // on fig000_5b the generic path took 16 % of the instructions). The model's bounds
  // (blends_scale.cpp): h at the ends, max L_k times the gain; the slope of docs/math.md §8.
  static void bounds(const Instr& out, const BoundsIO& io) { bounds_and_pick(out, io); }
  // bounds(), returning the child whose value h is at every point of the box or segment (outside
  // region III: ScaleOperator::sharp_everywhere), or -1: the walk prunes the other child by it.
  static int bounds_and_pick(const Instr& out, const BoundsIO& io) {
    const int s1 = io.child(0).slot, s2 = io.child(1).slot;
    const ScaleOperator op = load(io.K + out.in);
    const double L = std::max(io.L[s1], io.L[s2]) * op.gain() * (1 + 1e-12);
    const int sharp = op.sharp_everywhere(io.I[s1], io.I[s2]);
    io.L[out.out] = L;
    io.Q[out.out] = 0;
    if (!io.segment) {
      io.I[out.out] = op.range_and_slope(io.I[s1], io.I[s2], nullptr, nullptr, nullptr, sharp);
      io.D[out.out] = {-L, L};
      return sharp;
    }
    Interval slope;
    io.I[out.out] = op.range_and_slope(io.I[s1], io.I[s2], &io.D[s1], &io.D[s2], &slope, sharp);
    io.D[out.out] = BoundsIO::capped(slope, L);
    return sharp;
  }
};

// (Σ g_i^q)^(1/q), q = ±n, 002 Eq. 7. Constants (at in): positive, n, rest, the global bound.
struct RicciOp : Combination<RicciOp> {
  static std::vector<double> constants(const RicciParams& m, double global_L) {
    return {m.positive ? 1.0 : 0.0, m.n, static_cast<double>(m.rest), global_L};
  }
  static RicciParams load(const double* c) {
    return {c[0] != 0, c[1], static_cast<RicciArg>(static_cast<int>(c[2]))};
  }
  static double combine(const Instr& in, const double* K, double* x) {
    return ricci(load(K + in.in), x, nullptr, in.n, nullptr);
  }
  static double combine(const Instr& in, const double* K, double* x, Vec3* g, Vec3* grad) {
    return ricci(load(K + in.in), x, g, in.n, grad);
  }
  static Interval interval(const double* c, const Interval* x, const double* L, int n,
                           double* lipschitz) {
    *lipschitz = ricci_lipschitz(load(c), x, L, n, c[3]);
    return ricci_interval(load(c), x, n);
  }
  static Interval slope(const double* c, const Interval* x, const Interval* D, int n) {
    return ricci_slope(load(c), x, D, n);
  }
};

}  // namespace softtrace

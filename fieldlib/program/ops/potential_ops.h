// The instructions over one value slot: the potentials P(d) of a distance (docs/math.md §3), a
// soft object's strength, the offset, the complement, and the radius-transformed potential
// P(T(d, w)) (003), which reads a second slot and a register's box too.
//
// Rounding: the potentials are monotone and computed with O(1) operations on values of order 1:
// the ends' values ± 2^-50 (about 4 ulps of 1) hold every computed value in between.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "kernels/complement.h"
#include "kernels/offset.h"
#include "kernels/potentials.h"
#include "kernels/strength.h"
#include "kernels/transformed_potential.h"
#include "math/bound_util.h"
#include "math/convention.h"
#include "program/ops/op_io.h"

namespace softtrace {

// A non-increasing potential of distance slot in.in, its values lo = P(d.hi) and hi = P(max(0,
// d.lo)) at the ends of the distance's interval [d], with |P'| in `slope` over it: P over [d] and
// its slope bound (0 where d >= 1); along a segment dP/dt = P'(d) d' with P' in -slope, and 0
// while d >= 1.
inline void potential_bounds_of(const Instr& in, const BoundsIO& io, double lo, double hi,
                                Interval slope) {
  const Interval d = io.I[in.in];
  io.I[in.out] = {std::max(0.0, lo - 0x1p-50), std::min(1.0, hi + 0x1p-50)};
  io.L[in.out] = flat_product(d.lo >= 1 ? 0.0 : slope.hi, io.L[in.in]);
  if (!io.segment) return;
  io.D[in.out] = -slope * io.D[in.in];
  io.Q[in.out] = io.quiet_potential(in.in);
}
// The same with the values from the kernel `pot`.
template <class P>
void potential_bounds(const Instr& in, const BoundsIO& io, P pot, Interval slope) {
  const Interval d = io.I[in.in];
  potential_bounds_of(in, io, pot(d.hi), pot(std::max(0.0, d.lo)), slope);
}

// The potentials' point value and gradient from their kernel `pot(d, &dP)`.
template <class P>
void potential_value(const Instr& in, const PointIO& io, P pot) {
  io.S[in.out] = pot(io.S[in.in], nullptr);
}
template <class P>
void potential_gradient(const Instr& in, const GradIO& io, P pot) {
  double dP;
  const double v = pot(io.S[in.in].v, &dP);
  io.S[in.out] = GradIO::chain(v, dP, io.S[in.in]);
}

// Blanc's potential, 002 Eq. 2. Constants: s.
struct BlancOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = true;
  static std::vector<double> constants(double s) { return {s}; }
  static double load(const double* c) { return c[0]; }

  static void values(const Instr& in, const LaneIO& io) {
    blanc_lanes(io.slot(in.in), load(io.K + in.a), io.n, io.slot(in.out));
  }
  static void value(const Instr& in, const PointIO& io) {
    const double s = load(io.K + in.a);
    potential_value(in, io, [s](double d, double* dP) { return blanc(d, s, dP); });
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const double s = load(io.K + in.a);
    potential_gradient(in, io, [s](double d, double* dP) { return blanc(d, s, dP); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const double s = load(io.K + in.a);
    // Without slopes only the Lipschitz bound is wanted: the global one costs nothing. With them,
    // each end's value and slope from one kernel call (blanc_ends).
    double lo, hi;
    Interval slope(0, blanc_lipschitz(s));
    blanc_ends(s, io.I[in.in], &lo, &hi, io.slopes ? &slope : nullptr);
    potential_bounds_of(in, io, lo, hi, slope);
  }
};

// The potentials without a parameter: `pot(d, &dP)` lane by lane.
template <double (*pot)(double, double*)>
void plain_potential_values(const Instr& in, const LaneIO& io) {
  const double* d = io.slot(in.in);
  double* out = io.slot(in.out);
  for (int l = 0; l < io.n; ++l) out[l] = pot(d[l], nullptr);
}

// 1 - 22/9 d^2 + 17/9 d^4 - 4/9 d^6 (d < 1), Wyvill et al. No constants.
struct WyvillOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = true;
  static void values(const Instr& in, const LaneIO& io) { plain_potential_values<wyvill>(in, io); }
  static void value(const Instr& in, const PointIO& io) { potential_value(in, io, wyvill); }
  static void gradient(const Instr& in, const GradIO& io) { potential_gradient(in, io, wyvill); }
  static void bounds(const Instr& in, const BoundsIO& io) {
    potential_bounds(
        in, io, [](double d) { return wyvill(d, nullptr); },
        io.slopes ? wyvill_slope_range(io.I[in.in]) : Interval(0, wyvill_lipschitz()));
  }
};

// (1 - d^2)^2 (d < 1), POV-Ray's blob density. No constants. A polynomial: its slope range costs
// little anywhere.
struct MurakamiOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = true;
  static void values(const Instr& in, const LaneIO& io) {
    plain_potential_values<murakami>(in, io);
  }
  static void value(const Instr& in, const PointIO& io) { potential_value(in, io, murakami); }
  static void gradient(const Instr& in, const GradIO& io) { potential_gradient(in, io, murakami); }
  static void bounds(const Instr& in, const BoundsIO& io) {
    potential_bounds(
        in, io, [](double d) { return murakami(d, nullptr); }, murakami_slope_range(io.I[in.in]));
  }
};

// (1 - d^2)^3 (d < 1), Galin et al. 2020. No constants. A polynomial, as Murakami's.
struct CubicOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = true;
  static void values(const Instr& in, const LaneIO& io) { plain_potential_values<cubic>(in, io); }
  static void value(const Instr& in, const PointIO& io) { potential_value(in, io, cubic); }
  static void gradient(const Instr& in, const GradIO& io) { potential_gradient(in, io, cubic); }
  static void bounds(const Instr& in, const BoundsIO& io) {
    potential_bounds(
        in, io, [](double d) { return cubic(d, nullptr); }, cubic_slope_range(io.I[in.in]));
  }
};

// s · f: a soft object's strength. Constants: s.
struct StrengthOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = true;
  static std::vector<double> constants(double s) { return {s}; }
  static double load(const double* c) { return c[0]; }

  static void values(const Instr& in, const LaneIO& io) {
    const double* d = io.slot(in.in);
    double* out = io.slot(in.out);
    const double s = load(io.K + in.a);
    for (int l = 0; l < io.n; ++l) out[l] = strength_value(s, d[l]);
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = strength_value(load(io.K + in.a), io.S[in.in]);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const double s = load(io.K + in.a);
    const Dual& d = io.S[in.in];
    io.S[in.out] = {strength_value(s, d.v), strength_gradient(s, d.g)};
  }
  // s·f of a soft object f: 0 exactly where f is, so f's quiet start is its own
  // (kZeroWhenQuiet); d/dt (s f) = s df/dt, the ends swapped for s < 0.
  static void bounds(const Instr& in, const BoundsIO& io) {
    const double s = load(io.K + in.a);
    io.I[in.out] = strength_interval(s, io.I[in.in]);
    io.L[in.out] = strength_lipschitz(s, io.L[in.in]);
    io.D[in.out] = scaled(s, io.D[in.in]);
    io.Q[in.out] = io.Q[in.in];
  }
};

// s (f - c), 003 §2.1. Constants: s, c.
struct OffsetOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(double s, double c) { return {s, c}; }

  static void values(const Instr& in, const LaneIO& io) {
    const double* d = io.slot(in.in);
    double* out = io.slot(in.out);
    const double sc = io.K[in.a], lv = io.K[in.a + 1];
    for (int l = 0; l < io.n; ++l) out[l] = offset_value(sc, lv, d[l]);
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = offset_value(io.K[in.a], io.K[in.a + 1], io.S[in.in]);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const Dual& d = io.S[in.in];
    io.S[in.out] = {offset_value(io.K[in.a], io.K[in.a + 1], d.v),
                    offset_gradient(io.K[in.a], d.g)};
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const double s = io.K[in.a], c = io.K[in.a + 1];
    io.I[in.out] = offset_interval(s, c, io.I[in.in]);
    io.L[in.out] = offset_lipschitz(s, io.L[in.in]);
    // d/dt s·(f - c) = s·df/dt: an interval product, so a negative s swaps the ends. The offset
    // of a distance is no soft field: no quiet start.
    io.D[in.out] = scaled(s, io.D[in.in]);
    io.Q[in.out] = 0;
  }
};

// 1 - f, -f or 1/f by the convention. Constants: the convention.
struct ComplementOp : SlotToSlot {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(Convention conv) { return {static_cast<double>(conv)}; }
  static Convention load(const double* c) {
    return static_cast<Convention>(static_cast<int>(c[0]));
  }

  // The kernel's three forms as loops over the lanes (the guarded 1/f as a select).
  static void values(const Instr& in, const LaneIO& io) {
    const double* d = io.slot(in.in);
    double* out = io.slot(in.out);
    const int n = io.n;
    switch (load(io.K + in.a)) {
      case Convention::Soft:
        for (int l = 0; l < n; ++l) out[l] = 1 - d[l];
        break;
      case Convention::Zero:
        for (int l = 0; l < n; ++l) out[l] = -d[l];
        break;
      case Convention::Constructive:
        for (int l = 0; l < n; ++l) out[l] = 1 / (d[l] <= kCgFloor ? kCgFloor : d[l]);
        break;
    }
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = complement(load(io.K + in.a), io.S[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    Dual d = io.S[in.in];
    d.v = complement(load(io.K + in.a), d.v, &d.g);
    io.S[in.out] = d;
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const Convention conv = load(io.K + in.a);
    io.I[in.out] = complement_interval(conv, io.I[in.in]);
    io.L[in.out] = complement_lipschitz(conv, io.I[in.in], io.L[in.in]);
    // d/dt (1 - f) = d/dt (-f) = -df/dt exactly; for 1/f the bound either way. 1 - f and -f are
    // 0 nowhere in particular: no quiet start.
    io.D[in.out] =
        conv == Convention::Constructive ? Interval(-io.L[in.out], io.L[in.out]) : -io.D[in.in];
    io.Q[in.out] = 0;
  }
};

// P(T(d, w)), d = slot in, w constant or from f = slot n; reg = the point register whose box
// holds the support. Constants: TransformedPotential's own layout (constants(), load()).
struct RadiusTransformOp {
  static constexpr bool kPlaces = false;
  static constexpr bool kZeroWhenQuiet = true;
  static std::vector<double> constants(const TransformedPotential& t) { return t.constants(); }
  static TransformedPotential load(const double* c) { return TransformedPotential::load(c); }

  template <class Use, class Def>
  static void operands(Instr& in, const Program&, const Use& use, const Def& def) {
    use(kSlot, in.in);
    use(kSlot, in.n);
    use(kReg, in.reg);
    def(kSlot, in.out);
  }
  // The shared kernel lane by lane (T and P are branches and libm calls).
  static void values(const Instr& in, const LaneIO& io) {
    const TransformedPotential t = load(io.K + in.a);
    const double* d = io.slot(in.in);
    const double* f = io.slot(in.n);
    double* out = io.slot(in.out);
    const Vec3 none;
    for (int l = 0; l < io.n; ++l) out[l] = t.eval(d[l], none, f[l], none, nullptr);
  }
  static void value(const Instr& in, const PointIO& io) {
    const Vec3 none;
    io.S[in.out] = load(io.K + in.a).eval(io.S[in.in], none, io.S[in.n], none, nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const Dual &d = io.S[in.in], &f = io.S[in.n];
    Dual r;
    r.v = load(io.K + in.a).eval(d.v, d.g, f.v, f.g, &r.g);
    io.S[in.out] = r;
  }
  // 0 outside its support box, else the model's bounds from its distance's and modulation's
  // slots, unrefined. The model refines small boxes where [d]/[f] is wide over octants,
  // re-evaluating d and f on sub-boxes, which their slots cannot give; asking the model node for
  // those instead was measured (fig000_13d_star_contour at 80x60, one thread, medians of 3 benches
  // of 3 frames each): 0.256 s against 0.157 s unrefined, for 19.82 against 19.97 evaluations per
  // ray, and within 0.8 % of the evaluations on every scene with radius transforms. Along a
  // segment the slope is the chain rule's on d's and f's slopes (TransformedPotential::slope_along)
  // within [-L, L], and the field is 0 until the segment may enter the support box, or while
  // d >= 1 where that makes T = 1.
  // Where the register's box misses the support the field is 0 there: writes the bounds that say
  // so, which read neither operand (the walk then need not bound them), and returns true.
  static bool zero_outside(const Instr& in, const BoundsIO& io) {
    if (!load(io.K + in.a).outside_support(io.box(in.reg))) return false;
    io.I[in.out] = Interval(0);
    io.L[in.out] = 0;
    io.D[in.out] = Interval(0);
    io.Q[in.out] = 1;
    return true;
  }
  // The values at its segment's ends of the convex gauge instruction that wrote `slot` (the first
  // writer of it before `in` in the code: its consumer's operand), as its slope in this pass left
  // them in GaugeEnds (`last`, which a slope that did not compute both ends clears). False where
  // the writer is no such gauge or did not compute this segment's ends. *stray: how far the true
  // ends may lie from the computed ones (the register's pad and the coordinates' rounding).
  static bool gauge_ends(const Instr& in, const BoundsIO& io, int slot, double* v, double* stray) {
    const std::vector<Instr>& code = io.program->code;
    const std::ptrdiff_t k = &in - code.data();
    if (k < 0 || k >= static_cast<std::ptrdiff_t>(code.size())) return false;
    for (std::ptrdiff_t j = k - 1; j >= 0 && j >= k - 64; --j) {
      const Instr& w = code[j];
      if (w.op == Op::Translate || w.op == Op::Place || w.op == Op::Group || w.out != slot)
        continue;  // writes a register, announces a group, or another slot
      if (w.op != Op::SphericalProduct && w.op != Op::LpMetric) return false;
      const GaugeEnds* e = io.ends_of(w);
      if (!e || e->key != io.K + w.a || !e->last_valid) return false;
      const Vec3* S = io.segs + 2 * w.in;
      for (int i = 0; i < 2; ++i)
        if (!(e->last[i].x == S[i].x && e->last[i].y == S[i].y && e->last[i].z == S[i].z))
          return false;
      v[0] = e->last_f[0];
      v[1] = e->last_f[1];
      *stray = io.seg_pads[w.in] + 1e-12 * std::max(max_abs(S[0]), max_abs(S[1])) + 1e-300;
      return std::isfinite(v[0]) && std::isfinite(v[1]);
    }
    return false;
  }
  // d/f over the segment's points from its two ends: d/f at an end (the gauges' values there,
  // widened by their Lipschitz bounds over the ends' stray), moved along the segment by the range
  // of (d/f)' = (d' - r f')/f (B's loose r and f), from either end; then widened by |∇(d/f)| <=
  // (L_d + r L_f)/f times the stray for the computed points off the true segment. [d]/[f] over
  // the box ignores that d and f rise together: where the modulation lies close outside d (w
  // near 0.017 on 002 Fig. 3's cylinders) it takes w down to its clamp. Entire where not known.
  static Interval ratio_along(const Instr& in, const BoundsIO& io, const TransformedPotential& t,
                              const TransformedPotential::Bounds& B) {
    double d[2], f[2], sd, sf;
    if (!(B.f.lo > 0) || !std::isfinite(B.r.hi) || !gauge_ends(in, io, in.in, d, &sd) ||
        !gauge_ends(in, io, in.n, f, &sf))
      return Interval::entire();
    const double Ld = io.L[in.in], Lf = t.scale * io.L[in.n];
    if (!(std::isfinite(Ld) && std::isfinite(Lf))) return Interval::entire();
    const Interval dr = (io.D[in.in] - B.r * (io.D[in.n] * Interval(t.scale))) / B.f;
    const Interval span = dr * Interval(0, io.seg_length);
    Interval r = Interval::entire();
    for (int i = 0; i < 2; ++i) {
      const double fs = t.scale * f[i];
      const Interval di{widen_down(d[i] - Ld * sd, 1e-12), widen_up(d[i] + Ld * sd, 1e-12)};
      const Interval fi{widen_down(fs - Lf * sf, 1e-12), widen_up(fs + Lf * sf, 1e-12)};
      if (!(fi.lo > 0)) return Interval::entire();
      const Interval along = di / fi + (i == 0 ? span : -span);  // from A forward, from B back
      r = {std::max(r.lo, along.lo), std::min(r.hi, along.hi)};
    }
    const double off = (Ld + B.r.hi * Lf) / B.f.lo * std::max(sd, sf) * (1 + 1e-9) + 1e-300;
    if (!(r.lo <= r.hi) || !std::isfinite(off)) return Interval::entire();
    return {iv::down(r.lo - off), iv::up(r.hi + off)};
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    if (zero_outside(in, io)) return;
    Interval* I = io.I;
    double* L = io.L;
    const TransformedPotential t = load(io.K + in.a);
    TransformedPotential::Bounds B = t.bounds(I[in.in], L[in.in], I[in.n], L[in.n]);
    if (io.segment && io.slopes && t.src != WSource::Constant) {
      const Interval r = ratio_along(in, io, t, B);
      if (r.lo > B.r.lo || r.hi < B.r.hi) B = t.bounds(I[in.in], L[in.in], I[in.n], L[in.n], r);
    }
    I[in.out] = t.interval(B);
    L[in.out] = t.slope_bound(B);
    io.D[in.out] = {-L[in.out], L[in.out]};
    if (!io.segment) return;
    if (io.slopes)
      io.D[in.out] = BoundsIO::capped(t.slope_along(B, io.D[in.in], io.D[in.n]), L[in.out]);
    double q = io.box_entry(t.support, in.reg);
    if (t.src == WSource::Constant && t.T.outer_end(t.w) <= 1)
      q = std::max(q, io.quiet_potential(in.in));
    io.Q[in.out] = q;
  }
};

}  // namespace softtrace

// What an op's kernel struct (ops.h) reads and writes in each evaluator: the storage of the
// values, gradient and bounds passes, and the bounds pass's shared segment geometry. The
// evaluators (eval/) own these buffers in their Workspace; the op structs see only these views, so
// each op's maths for every domain sits in its one struct, inlined into the evaluators' loops.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "kernels/convex_slope.h"
#include "math/box.h"
#include "math/interval.h"
#include "math/vec.h"
#include "program/program.h"

namespace softtrace {

// The largest batch the values evaluator takes in one call.
constexpr int kBatch = 16;

// The storage pass's two spaces of values (program_storage.cpp).
enum Space { kSlot = 0, kReg = 1 };

// The operand shapes the op structs share (program_storage.cpp's operands()): calls use(space,
// id&) for every value the instruction reads, then def(space, id&) for the one it writes.
// A distance (or an oracle): a slot from a point register.
struct RegisterToSlot {
  static constexpr bool kPlaces = false;  // no box or segment that pruning needs
  template <class Use, class Def>
  static void operands(Instr& in, const Program&, const Use& use, const Def& def) {
    use(kReg, in.in);
    def(kSlot, in.out);
  }
};
// A function of one slot (potentials, strength, offset, complement).
struct SlotToSlot {
  static constexpr bool kPlaces = false;
  template <class Use, class Def>
  static void operands(Instr& in, const Program&, const Use& use, const Def& def) {
    use(kSlot, in.in);
    def(kSlot, in.out);
  }
};
// A placement: a point register to a new one, whose box or segment pruning needs too.
struct RegisterToRegister {
  static constexpr bool kPlaces = true;
  template <class Use, class Def>
  static void operands(Instr& in, const Program&, const Use& use, const Def& def) {
    use(kReg, in.in);
    def(kReg, in.out);
  }
};
// An n-ary instruction: its children's slots args[a..a+n) to a slot.
struct SlotsToSlot {
  static constexpr bool kPlaces = false;
  template <class Use, class Def>
  static void operands(Instr& in, Program& p, const Use& use, const Def& def) {
    for (int j = in.a; j < in.a + in.n; ++j) use(kSlot, p.args[j]);
    def(kSlot, in.out);
  }
};

// The values pass: slot s, lane l at S[s * kBatch + l]; register r, axis i, lane l at
// R[(r * 3 + i) * kBatch + l]; n lanes.
struct LaneIO {
  double* S;
  double* R;
  const double* K;
  const int32_t* args;
  int n;

  double* slot(int s) const { return S + s * kBatch; }
  double* reg(int r, int axis) const { return R + (r * 3 + axis) * kBatch; }
};

// One point: slot s at S[s], register r at R[r].
struct PointIO {
  double* S;
  Vec3* R;
  const double* K;
  const int32_t* args;
};

// The gradient pass (forward mode): every slot carries its value and its gradient with respect to
// the world point, every point register its Jacobian with respect to the world point.
struct Dual {
  double v;
  Vec3 g;
};
struct LocalFrame {
  Vec3 p;
  Mat3 J;         // ∂(local point)/∂(world point)
  bool identity;  // J = I: gradients pass unchanged (no 0·inf where a gradient is infinite)
};

struct GradIO {
  Dual* S;
  LocalFrame* R;
  const double* K;
  const int32_t* args;

  // A kernel of the point register in.in: its value, and its local gradient pulled back to the
  // world point (Jᵀg; passed unchanged where J = I, so an infinite gradient meets no 0·inf).
  template <class Kernel>
  void local(const Instr& in, const Kernel& kernel) const {
    const LocalFrame& f = R[in.in];
    Vec3 g;
    const double v = kernel(f.p, &g);
    S[in.out] = {v, f.identity ? g : f.J.transposed_times(g)};
  }
  // A potential's value and slope applied to the distance's dual number (P' = 0 gives a zero
  // gradient even where ∇d is infinite).
  static Dual chain(double v, double dP, const Dual& d) { return {v, dP == 0 ? Vec3{} : d.g * dP}; }
  // An n-ary instruction's children's values and gradients, for kernels that take them as arrays.
  void gather(const Instr& in, double* x, Vec3* g) const {
    for (int j = 0; j < in.n; ++j) {
      x[j] = S[args[in.a + j]].v;
      g[j] = S[args[in.a + j]].g;
    }
  }
};

// Rounding in the bounds pass. Instead of rounding every interval operation outward (nextafter),
// each instruction's result is widened once, by a bound on the rounding error of the few
// operations that made it (each op's bounds() says which).
constexpr double kTiny = 1e-300;
constexpr double kEps = 0x1p-52;
// How far a computed point may stray from the segment after a step with these magnitudes (each
// step's rounding is a few ulps of its operands; 1e-12 is thousands).
constexpr double kSegmentRounding = 1e-12;

inline double widen_down(double v, double rel) {
  return v - (std::abs(v) * rel + kTiny);
}
inline double widen_up(double v, double rel) {
  return v + (std::abs(v) * rel + kTiny);
}

// The bounds pass over a box, or along a segment (eval_bounds.cpp): per slot its value interval
// I, Lipschitz bound L, and on a segment its slope D (d/dt along it) and quiet start Q
// (Workspace::quiet); per register its box, and on a segment the segment's ends and pad.
struct BoundsIO {
  const Program* program;
  const double* K;
  Box* boxes;  // (off a segment: on one, box() makes them)
  Interval* I;
  double* L;
  Interval* D;
  double* Q;
  Vec3* segs;  // register r's segment ends at [2r], [2r + 1]
  double* seg_pads;
  GaugeEnds* ends;    // GaugeEnds::kTable entries (convex_slope.h)
  bool bounds;        // false: only pruning (placements still carry their boxes)
  bool segment;       // along a segment rather than over a box
  bool slopes;        // on a segment that asks for its slope (Segment::slopes)
  double seg_length;  // the segment's length in the world: t runs over [0, length]
  // An n-ary instruction's group and its kept children (their indices into group->children),
  // set by the walk before it asks for the combination's bounds.
  const Group* group = nullptr;
  const int32_t* kept = nullptr;

  // Register r's box: on a segment, the segment's own box (grown by its pad), tighter than the
  // box carried through a rotation and only made where an instruction asks for it.
  Box box(int r) const {
    if (!segment) return boxes[r];
    const Vec3* S = segs + 2 * r;
    return segment_box(S[0], S[1], seg_pads[r]);
  }

  // X·n over register r's segment (n a unit vector): X·n is affine along it, so its range is that
  // between the ends, grown by how far the computed points may stray and the dot's rounding.
  Interval dot_on_segment(const Vec3& n, int r) const {
    const Vec3* S = segs + 2 * r;
    const double d0 = dot(S[0], n), d1 = dot(S[1], n);
    const double grow =
        seg_pads[r] + kSegmentRounding * std::max(max_abs(S[0]), max_abs(S[1])) + kTiny;
    return {std::min(d0, d1) - grow, std::max(d0, d1) + grow};
  }

  // The rate of X·n along register r's segment per unit of the ray's t: (B - A)·n / len, padded
  // for the rounding of the register's segment ends (as ellipsoid_on_segment). Entire for a
  // degenerate segment.
  Interval rate_on_segment(const Vec3& n, int r) const {
    const Vec3 e = segment_step(r);
    return padded_rate(dot(e, n), rate_pad(e));
  }
  Vec3 segment_step(int r) const { return segs[2 * r + 1] - segs[2 * r]; }
  static double rate_pad(const Vec3& e) { return 1e-9 * length(e) + kTiny; }
  // k / len, grown by pad and by the division's rounding.
  Interval padded_rate(double k, double pad) const {
    const Interval rate{widen_down((k - pad) / seg_length, 1e-12),
                        widen_up((k + pad) / seg_length, 1e-12)};
    if (!(std::isfinite(rate.lo) && std::isfinite(rate.hi))) return Interval::entire();
    return rate;
  }

  // The local coordinates' rates along register r's segment (rate_on_segment along each axis),
  // for the axis-aligned gauges' slopes (lp_metric_bounds, spherical_product_bounds).
  void axis_rates(int r, Interval* rate) const {
    const Vec3 e = segment_step(r);
    const double pad = rate_pad(e);
    for (int i = 0; i < 3; ++i) rate[i] = padded_rate(e[i], pad);
  }

  static Interval capped(Interval slope, double L) {
    if (std::isnan(slope.lo) || std::isnan(slope.hi)) return {-L, L};
    return {std::max(-L, slope.lo), std::min(L, slope.hi)};
  }

  // A potential is 0 where its distance is >= 1.
  double quiet_potential(int d) const { return I[d].lo >= 1 ? 1.0 : Q[d]; }

  // A gauge with its slope along the segment in D[out] (uncapped): capped by its Lipschitz bound;
  // it stays >= 1 all along only where it does over the whole box.
  void gauge_segment_facts(int out) const {
    D[out] = capped(D[out], L[out]);
    Q[out] = I[out].lo >= 1 ? 1 : 0;
  }

  // A distance bounded over its register's box only: its slope along the segment is the Lipschitz
  // bound either way, and it stays >= 1 all along only where it does over the whole box.
  void segment_facts_from_box(int out) const {
    D[out] = {-L[out], L[out]};
    Q[out] = I[out].lo >= 1 ? 1 : 0;
  }

  // The fraction of register r's segment before which it cannot be in box s (1 where it never
  // enters): the slab test, with the box grown by how far the computed points may stray and by
  // the rounding of the slab's quotients (a few ulps of the coordinates, far inside 1e-12).
  double box_entry(const Box& s, int r) const {
    if (!s.bounded()) return 0;
    const Vec3* S = segs + 2 * r;
    const double grow =
        seg_pads[r] +
        kSegmentRounding * std::max({max_abs(S[0]), max_abs(S[1]), max_abs(s.lo), max_abs(s.hi)}) +
        kTiny;
    double enter = 0, leave = 1;
    for (int i = 0; i < 3; ++i) {
      const double lo = s.lo[i] - grow, hi = s.hi[i] + grow, a = S[0][i], e = S[1][i] - a;
      if (e == 0) {
        if (a < lo || a > hi) return 1;
        continue;
      }
      double ta = (lo - a) / e, tb = (hi - a) / e;
      if (e < 0) std::swap(ta, tb);
      // NaN ends compare false and leave [enter, leave] as it was.
      enter = std::max(enter, ta);
      leave = std::min(leave, tb);
    }
    if (enter > leave) return 1;
    return enter * (1 - 1e-9);
  }

  // The table entry of a program instruction `in` (an element of program->code), or null.
  GaugeEnds* ends_of(const Instr& in) const {
    const uintptr_t k =
        (reinterpret_cast<uintptr_t>(&in) - reinterpret_cast<uintptr_t>(program->code.data())) /
        sizeof(Instr);  // an address below the code wraps to a large k
    if (k >= program->code.size()) return nullptr;
    return ends + k % GaugeEnds::kTable;
  }

  // Child j of the n-ary instruction being combined (j < its kept count).
  const Group::Child& child(int j) const { return group->children[kept[j]]; }
};

}  // namespace softtrace

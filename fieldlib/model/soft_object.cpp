#include "model/soft_object.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "describe/building.h"
#include "kernels/radius_transforms.h"
#include "kernels/transformed_potential.h"
#include "math/bound_util.h"
#include "model/modulation_check.h"
#include "model/potential.h"
#include "model/program_builder.h"
#include "model/strength.h"
#include "program/ops/potential_ops.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// P ∘ d   — 000 Eq. 9, 002 Eq. 1
class SoftObject final : public FieldNode {
 public:
  SoftObject(NodePtr distance, PotentialPtr potential)
      : d_(std::move(distance)), P_(std::move(potential)) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const double d = d_->eval(p, grad);
    double dP;
    const double v = P_->eval(d, grad ? &dP : nullptr);
    if (grad) *grad = dP == 0 ? Vec3{} : *grad * dP;
    return v;
  }
  // A polynomial potential of an ellipsoid's distance is a polynomial blob.
  bool polynomial_blob(PolynomialBlob* b) const override {
    return potential_in_r(P_->type(), &b->c2, &b->c3) && d_->polynomial_blob(b);
  }
  double lipschitz() const override { return flat_product(P_->lipschitz(), d_->lipschitz()); }
  Box region(double level, Side side) const override {
    if (side == Side::Above && level > 0) return d_->region(1, Side::Below);
    return Box::unbounded();
  }
  // The distance's code, then one potential instruction.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{P_->op()};
    i.in = b.compile(*d_, reg);
    i.out = b.new_slot();
    if (P_->op() == Op::Blanc) i.a = b.consts(BlancOp::constants(P_->parameter()));
    return b.emit(i);
  }
  NodePtr clone() const override {
    NodePtr d = d_->clone();
    if (!d) return nullptr;
    return std::make_unique<SoftObject>(std::move(d), P_->clone());
  }

 private:
  // P over d's range, and sup|P'| there times d's bound.
  NodeBounds box_bounds(const Box& b) const override {
    const NodeBounds d = d_->bounds(b);
    return {P_->interval(d.value), flat_product(P_->lipschitz(d.value), d.lipschitz)};
  }

  NodePtr d_;
  PotentialPtr P_;
};

// P ∘ T ∘ d   — 000 Eqs. 13–15, 002 Eqs. 10–14, docs/math.md §4.2–§4.9; the kernels are
// transformed_potential.h's, shared with the RadiusTransform instruction.
class TransformedSoftObject final : public FieldNode {
 public:
  TransformedSoftObject(NodePtr d, PotentialPtr P, RadiusProfile T, double w)
      : d_(std::move(d)), K_{P->kind(), T, WSource::Constant, w, 1, 0, 0, Box{}} {
    init();
  }
  TransformedSoftObject(NodePtr d, PotentialPtr P, RadiusProfile T, WSource src, NodePtr f,
                        double f_scale, double w_min)
      : d_(std::move(d)), f_(std::move(f)), K_{P->kind(), T, src, 1, f_scale, w_min, 0, Box{}} {
    init();
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    Vec3 gd, gf;
    const double d = d_->eval(p, grad ? &gd : nullptr);
    double fm = 0;
    if (d > 0 && f_) fm = f_->eval(p, grad ? &gf : nullptr);
    return K_.eval(d, gd, fm, gf, grad);
  }

  double lipschitz() const override { return K_.lipschitz(); }

  Box region(double level, Side side) const override {
    if (side != Side::Above || level <= 0) return Box::unbounded();
    switch (K_.src) {
      case WSource::Constant:
        return d_->region(K_.T.outer_end(K_.w), Side::Below);
      case WSource::Outer:
        return f_->region(0.5 / K_.scale, Side::Below)
            .united(d_->region(0.5 * (1 + K_.w_min), Side::Below));
      case WSource::Inner:
        return d_->region(1, Side::Below);
    }
    return Box::unbounded();
  }

  // The distance's code, the modulation's (for a modulated w), then one RadiusTransform
  // instruction, whose bounds are this node's without the octants (eval_bounds.cpp says why).
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{Op::RadiusTransform};
    i.in = b.compile(*d_, reg);
    i.n = f_ ? b.compile(*f_, reg) : i.in;
    i.reg = reg;
    i.a = b.consts(RadiusTransformOp::constants(K_));
    i.out = b.new_slot();
    return b.emit(i);
  }

 private:
  // Outside the support box the field is exactly 0: no bound is needed there. This matters in
  // blends, where every stretch box asks every child, and the decorrelated [d]/[f] bounds of a
  // far-away child are loose (measured on [002] Fig. 8(c): thousands of evaluations per ray).
  NodeBounds box_bounds(const Box& b) const override {
    if (K_.outside_support(b)) return {Interval(0), 0};
    NodeBounds out;
    refined(b, kRefine, &out.value, &out.lipschitz);
    return out;
  }

  void init() {
    K_.d_lipschitz = d_->lipschitz();
    K_.support = region(std::numeric_limits<double>::min(), Side::Above);
  }

  using Bounds = TransformedPotential::Bounds;

  // [d]/[f] loses the correlation of d and f (their ratio is constant along rays from a common
  // centre), so [w] can reach the clamp although w stays well above it in the box; up to two
  // levels of octants, only where [w] is that wide, restore most of it (measured for T_sn on
  // boxes of 5 % of the object's size at its surface: bounds of 1e7 drop to ~1e2 against sampled
  // slopes of ~10). Every level is sound; the smaller bound is kept.
  static constexpr int kRefine = 2;  // octant levels: at most 8 + 64 sub-boxes
  // Octants cost up to 72 bounds; boxes above this fraction of the support's diagonal are not
  // refined. Those are the tracer's long segments, which it halves along the ray itself for a
  // bound or two (measured over scenes/ at 80x60 and 320x240: the same evaluations per ray, and
  // 0.2-0.7x the time on the contour and modulated scenes; 1/16 keeps the 5 % boxes of
  // SurfaceDefined.BoxBoundsStayUsefulAtTheSurface refined).
  static constexpr double kRefineMaxSize = 1.0 / 16;

  // The interval and the Lipschitz bound over b: each the tighter of b's own and its octants' (one
  // walk over the octants serves both).
  void refined(const Box& b, int levels, Interval* I, double* L) const {
    const Bounds B = child_bounds(b);
    *I = K_.interval(B);
    *L = K_.slope_bound(B);
    if (levels == 0 || !decorrelated(B, b) || !worth_refining(b)) return;
    Interval h(kInf, -kInf);
    double m = 0, Ls;
    for (const Box& s : octants(b)) {
      Interval Is;
      refined(s, levels - 1, &Is, &Ls);
      h = hull(h, Is);
      m = std::max(m, Ls);
    }
    *I = {std::max(I->lo, h.lo), std::min(I->hi, h.hi)};
    *L = std::min(*L, m);
  }
  bool decorrelated(const Bounds& B, const Box& b) const {
    return K_.src != WSource::Constant && b.bounded() && B.w.lo < 0.25 * B.w.hi && B.T.lo < B.T.hi;
  }
  bool worth_refining(const Box& b) const {
    return !K_.support.bounded() || b.diagonal() <= kRefineMaxSize * K_.support.diagonal();
  }
  static std::array<Box, 8> octants(const Box& b) {
    std::array<Box, 8> out;
    const Vec3 c = b.center();
    for (int k = 0; k < 8; ++k)
      for (int i = 0; i < 3; ++i) {
        const bool hi = (k >> i) & 1;
        out[k].lo[i] = hi ? c[i] : b.lo[i];
        out[k].hi[i] = hi ? b.hi[i] : c[i];
      }
    return out;
  }

  // The shared kernel's bounds from d's and f's over b (their intervals and Lipschitz bounds).
  Bounds child_bounds(const Box& b) const {
    const NodeBounds d = d_->bounds(b);
    const NodeBounds f = f_ ? f_->bounds(b) : NodeBounds{};
    return K_.bounds(d.value, d.lipschitz, f.value, f.lipschitz);
  }

  NodePtr d_, f_;  // f_: the modulation (or contour) field, for a modulated w
  TransformedPotential K_;
};

// T_a*, T_s* and contour: w from the modulation (or contour) node `key` (docs/math.md §4.5-§4.8).
NodePtr create_modulated(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx,
                         RadiusProfile profile, WSource src, const char* key, double scale) {
  const double w_min = r.number("w_min", 1e-4);
  check_same_skeleton(r, key, ctx);
  NodePtr f = build_node(r, key, ctx);
  const FieldNode &dn = *d, &fn = *f;
  NodePtr node = std::make_unique<TransformedSoftObject>(
      std::move(d), std::move(P), std::move(profile), src, std::move(f), scale, w_min);
  check_modulation_side(r, key, *node, dn, fn, scale, src == WSource::Outer, ctx);
  return node;
}

}  // namespace

NodePtr create_T_n(const Params& r, NodePtr d, PotentialPtr P, const BuildContext&) {
  const double w1 = r.number("w1"), w2 = r.number("w2");
  r.check(w2 <= 2 * w1, "w2", "expected w2 <= 2*w1, else T_n is not monotone (docs/math.md §4.2)");
  return std::make_unique<TransformedSoftObject>(std::move(d), std::move(P),
                                                 make_profile_n(W2Rule::Fixed, w2), w1);
}
NodePtr create_T_l(const Params& r, NodePtr d, PotentialPtr P, const BuildContext&) {
  return std::make_unique<TransformedSoftObject>(std::move(d), std::move(P), make_profile_l(),
                                                 r.number("w1"));
}
NodePtr create_T_r(const Params& r, NodePtr d, PotentialPtr P, const BuildContext&) {
  return std::make_unique<TransformedSoftObject>(std::move(d), std::move(P), make_profile_r(),
                                                 r.number("w2"));
}
NodePtr create_T_an(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_n(W2Rule::Double),
                          WSource::Outer, "modulation", 1);
}
NodePtr create_T_al(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_l(), WSource::Outer,
                          "modulation", 1);
}
NodePtr create_T_sn(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_n(W2Rule::Equal),
                          WSource::Inner, "modulation", 1);
}
NodePtr create_T_sr(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_r(), WSource::Inner,
                          "modulation", 1);
}
// [000]'s contour surface fc = 1 is T_an with f_a = fc/2 (docs/math.md §4.8, [VIR-2]).
NodePtr create_contour(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_n(W2Rule::Double),
                          WSource::Outer, "contour", 0.5);
}

NodePtr create_soft_object(const Params& p, const BuildContext& ctx) {
  const double s = p.number("strength", 1.0);
  p.check(s != 0, "strength", "expected strength != 0 (s = 0 gives no field)");
  NodePtr d = build_node(p, "distance", ctx);
  PotentialPtr P = p.has("potential") ? build_potential(p.object("potential")) : make_blanc(0);
  if (!p.has("radii"))
    return with_strength(std::make_unique<SoftObject>(std::move(d), std::move(P)), s);
  BuildContext inner = ctx;
  inner.skeleton = skeleton_of(p.raw().at("distance"));
  return with_strength(build_radius_transform(p.object("radii"), std::move(d), std::move(P), inner),
                       s);
}

}  // namespace softtrace

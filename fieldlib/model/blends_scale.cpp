// The scale method BSA2 / BSS2 (docs/math.md §6.3; 000 §II.C.3, Eq. 8): h solving
// G(h) = h^2 B_H(σ(x/h - 1)) = a h^2 + b h + c = 0 on region III, min/max elsewhere; σ = +1 for
// BSA2 (y = x/h - 1), σ = -1 for BSS2 (y = 1 - x/h).
// Bounds, derived:
// - Monotone: by the implicit function theorem ∂h/∂x_j = ∂_jB_H(y) / Σ_k (x_k/h) ∂_kB_H(y)
//   (both for σ = ±1, from ∂G/∂x_j = σ h ∂_jB_H and ∂G/∂h = -σ Σ_k x_k ∂_kB_H at a root). On the
//   arc in Q = [0,r1]×[0,r2], which runs from the tangency (0,r2) to (r1,0) with B_H > 0 on the
//   corner side, both ∂_kB_H have the same sign, so ∂h/∂x_j >= 0; the interval is therefore B at
//   the ends of the children's intervals ([SC-2] continuity joins the pieces).
// - Lipschitz: Σ_k (x_k/h) ∂h/∂x_k = 1 (Euler, degree-1 homogeneity [SC-4]) with x_k/h = 1 + y_k
//   >= 1 (BSA2) or x_k/h = 1 - y_k >= 1 - r_k (BSS2). Maximising Σ ∂_k h L_k under that gives
//   |∇B| <= max_k L_k (BSA2) and max_k L_k/(1 - r_k) (BSS2); min/max outside III need max_k L_k.
// - Regions: h lies between min x and the chord value h_c = (r2 x1 + r1 x2)/(r1 r2 + r1 + r2)
//   (BSA2), or between max x and h_c = (r2 x1 + r1 x2)/(r1 + r2 - r1 r2) (BSS2) (A6), so κ_A min x
//   <= BSA2 <= min x with κ_A = (r1+r2)/(r1 r2+r1+r2) and max x <= BSS2 <= max x/κ_S with κ_S =
//   (r1+r2-r1 r2)/(r1+r2) (for positive arguments; with min x <= 0 resp. max x <= 0 the operator is
//   min resp. max).
#include <algorithm>
#include <cmath>

#include "describe/building.h"
#include "model/blends.h"
#include "model/nary_node.h"
#include "model/program_builder.h"
#include "model/strength.h"
#include "program/ops/nary_ops.h"

namespace softtrace {

namespace {

// BSA2 or BSS2 of two children   — 000 §II.C.3, docs/math.md §6.3.2, §6.3.3
class Scale final : public NaryNode<Scale> {
 public:
  // `children`: exactly two (the kinds table).
  Scale(std::vector<NodePtr> children, double r1, double r2, double p, bool bsa)
      : NaryNode(std::move(children)), op_(r1, r2, p, bsa), bsa_(bsa) {
    kappa_ = bsa ? (r1 + r2) / (r1 * r2 + r1 + r2) : (r1 + r2 - r1 * r2) / (r1 + r2);
    gain_ = bsa ? 1.0 : 1 / (1 - std::max(r1, r2));
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    Vec3 g1, g2;
    const double x1 = c_[0]->eval(p, grad ? &g1 : nullptr),
                 x2 = c_[1]->eval(p, grad ? &g2 : nullptr);
    double dh[2];
    const double h = op_(x1, x2, grad ? dh : nullptr);
    if (grad) *grad = g1 * dh[0] + g2 * dh[1];
    return h;
  }
  double lipschitz() const override {
    return std::max(c_[0]->lipschitz(), c_[1]->lipschitz()) * gain_ * (1 + 1e-12);
  }
  Box region(double level, Side side) const override {
    // BSA2: {B >= l} needs both x_i >= l; {B <= c} needs some x_i <= c/κ_A (c > 0).
    // BSS2: {B <= c} needs both x_i <= c; {B >= l} needs some x_i >= l κ_S (l > 0).
    const bool both = bsa_ == (side == Side::Above);
    double l = level;
    if (!both && level > 0) l = bsa_ ? level / kappa_ : level * kappa_;
    const Box a = c_[0]->region(l, side), c = c_[1]->region(l, side);
    return both ? a.intersected(c) : a.united(c);
  }

  // The children's code as a group (never pruned), then one instruction with r1, r2, p inline:
  // along a segment its slope is the chain rule on the children's (docs/math.md §8, "Slopes along a
  // segment").
  int compile(ProgramBuilder& b, int reg) const override {
    return b.nary(Op::Scale, c_, reg, b.consts(ScaleOp::constants(op_)));
  }

 private:
  friend NaryNode;

  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    return {op_.range(I[0], I[1]), std::max(L[0], L[1]) * gain_ * (1 + 1e-12)};
  }

  ScaleOperator op_;
  bool bsa_;
  double kappa_, gain_;
};

NodePtr create_scale(const Params& p, const BuildContext& ctx, bool union_op) {
  if (ctx.convention == Convention::Zero)
    p.fail("type", "scale_* applies to soft or constructive objects (docs/math.md §6.3)");
  const double r1 = p.number("r1"), r2 = p.number("r2"), pp = p.number("p");
  p.check(pp < r1 * r2, "p", "expected p < r1*r2 (docs/math.md §6.1)");
  // Constructive: union BSA2, intersection BSS2; soft fields swap the roles ([CONV-2], §6.3.4).
  const bool bsa = (ctx.convention == Convention::Constructive) == union_op;
  if (!bsa) {
    p.check(r1 < 1, "r1", "expected 0 < r1 < 1 for BSS2 (docs/math.md §6.3.3, R24)");
    p.check(r2 < 1, "r2", "expected 0 < r2 < 1 for BSS2 (docs/math.md §6.3.3, R24)");
  }
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  refuse_negative_strength(p, ctx.kind->name);
  return std::make_unique<Scale>(std::move(c), r1, r2, pp, bsa);
}

}  // namespace

NodePtr create_scale_union(const Params& p, const BuildContext& ctx) {
  return create_scale(p, ctx, true);
}
NodePtr create_scale_intersection(const Params& p, const BuildContext& ctx) {
  return create_scale(p, ctx, false);
}

}  // namespace softtrace

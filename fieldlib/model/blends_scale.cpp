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
#include "model/strength.h"

namespace softtrace {

ScaleOperator::ScaleOperator(double r1, double r2, double p, bool bsa)
    : r1_(r1), r2_(r2), p_(p), s_(bsa ? 1 : -1) {
  a_ = (1 + 2 * s_ * r2_) * r1_ * r1_ + (1 + s_ * r1_) * (1 + s_ * r1_) * r2_ * r2_ + 2 * p_;
  b1_ = -2 * ((1 + s_ * r1_) * r2_ * r2_ + p_);
  b2_ = -2 * ((1 + s_ * r2_) * r1_ * r1_ + p_);
}

bool ScaleOperator::region3(double x1, double x2) const {
  if (!(x1 > 0 && x2 > 0)) return false;
  if (s_ > 0) return x1 / (1 + r1_) < x2 && x2 < (1 + r2_) * x1;
  return (1 - r1_) * x2 < x1 && (1 - r2_) * x1 < x2;
}

double ScaleOperator::operator()(double x1, double x2, double dh[2]) const {
  const bool first = s_ > 0 ? x1 <= x2 : x1 >= x2;  // which argument min/max picks
  const double sharp = first ? x1 : x2;
  if (dh) {
    dh[0] = first ? 1 : 0;
    dh[1] = first ? 0 : 1;
  }
  if (!region3(x1, x2)) return sharp;
  const double b = b1_ * x1 + b2_ * x2;
  const double c = r1_ * r1_ * x2 * x2 + r2_ * r2_ * x1 * x1 + 2 * p_ * x1 * x2;
  const double q = std::sqrt(std::max(b * b - 4 * a_ * c, 0.0));
  // The "+" root for BSA2 and the "-" root for BSS2, each in its cancellation-free form (A6).
  double h;
  if (s_ > 0)
    h = b > 0 ? 2 * c / (-b - q) : (-b + q) / (2 * a_);
  else
    h = b < 0 ? 2 * c / (-b + q) : (-b - q) / (2 * a_);
  if (!std::isfinite(h)) return sharp;
  if (dh) {  // implicit function theorem on G(h; x) = a h^2 + b h + c
    const double Gh = 2 * a_ * h + b;
    const double G1 = h * b1_ + 2 * r2_ * r2_ * x1 + 2 * p_ * x2;
    const double G2 = h * b2_ + 2 * r1_ * r1_ * x2 + 2 * p_ * x1;
    const double d1 = -G1 / Gh, d2 = -G2 / Gh;
    if (std::isfinite(d1) && std::isfinite(d2)) {
      dh[0] = d1;
      dh[1] = d2;
    }
  }
  return h;
}

namespace {

// BSA2 or BSS2 of two children   — 000 §II.C.3, docs/math.md §6.3.2, §6.3.3
class Scale final : public NaryNode {
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

 private:
  NodeBounds combine(const Box&, const Interval* I, const double* L) const override {
    return {range(I[0], I[1]), std::max(L[0], L[1]) * gain_ * (1 + 1e-12)};
  }

  // B is non-decreasing in both arguments: its range is B at the ends, widened for rounding.
  Interval range(Interval i1, Interval i2) const {
    const double lo = op_(i1.lo, i2.lo, nullptr), hi = op_(i1.hi, i2.hi, nullptr);
    return iv::out(lo - 1e-13 * std::abs(lo), hi + 1e-13 * std::abs(hi));
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

// Ricci's super-ellipsoidal operators (docs/math.md §5.3 constructive, §5.4 soft): power means
// B = (Σ g_i^q)^(1/q) of g_i = f_i, 1 - f_i or 1/f_i; the kernels, and the bounds' derivation,
// are in ricci.h.
#include <cmath>
#include <vector>

#include "describe/building.h"
#include "kernels/ricci.h"
#include "math/scratch.h"
#include "model/blends.h"
#include "model/nary_node.h"
#include "model/node_util.h"
#include "model/program_builder.h"
#include "model/strength.h"
#include "program/ops/nary_ops.h"

namespace softtrace {

namespace {

// (Σ g_i^q)^(1/q)   — 000 Eq. 6, 002 Eqs. 7–8 (ricci.h)
class Ricci final : public NaryNode<Ricci> {
 public:
  Ricci(std::vector<NodePtr> c, RicciParams m) : NaryNode(std::move(c)), m_(m) {
    std::vector<Interval> f;
    std::vector<double> L;
    for (const auto& c : c_) {
      f.push_back(global_range(*c));
      L.push_back(c->lipschitz());
    }
    global_L_ = ricci_global_lipschitz(m_, f.data(), L.data(), c_.size());
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = c_.size();
    Scratch<double> f(k);
    Scratch<Vec3> gf(k);
    for (size_t i = 0; i < k; ++i) f[i] = c_[i]->eval(p, grad ? &gf[i] : nullptr);
    return ricci(m_, f.data(), gf.data(), k, grad);
  }
  double lipschitz() const override { return global_L_; }
  // Regions: q = n gives max g <= B <= k^(1/n) max g; q = -n gives k^(-1/n) min g <= B <= min g.
  Box region(double level, Side side) const override {
    const double k = static_cast<double>(c_.size());
    // B >= 0 always: {B <= c < 0} is empty.
    if (side == Side::Below && level < 0) return Box();
    const bool any = m_.positive == (side == Side::Above);  // a union of the arguments' regions
    double l = level;
    if (m_.positive && side == Side::Above) l = level * std::pow(k, -1 / m_.n);
    if (!m_.positive && side == Side::Below) l = level * std::pow(k, 1 / m_.n);
    if (side == Side::Above && level <= 0) return Box::unbounded();
    Box b = any ? Box() : Box::unbounded();
    for (size_t i = 0; i < c_.size(); ++i) {
      const Box r = arg_region(i, l, side);
      b = any ? b.united(r) : b.intersected(r);
    }
    return b;
  }
  // The children's code as a group, never pruned (nary prunes only sums' children; a soft union's
  // children that are 0 outside their supports could be dropped there too, not taken here), then
  // one instruction with the parameters and the global bound inline.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.nary(Op::Ricci, c_, reg, b.consts(RicciOp::constants(m_, global_L_)));
  }

 private:
  friend NaryNode;

  // B at the ends of the children's intervals, and the bound of ricci.h, from the children's.
  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    const size_t k = c_.size();
    return {ricci_interval(m_, I, k), ricci_lipschitz(m_, I, L, k, global_L_)};
  }

  // The region of child i where its argument g_i >= l (Above) or <= l (Below).
  Box arg_region(size_t i, double l, Side side) const {
    const Side other = side == Side::Above ? Side::Below : Side::Above;
    switch (ricci_arg_kind(m_, i)) {
      case RicciArg::Same:
        return c_[i]->region(l, side);
      case RicciArg::SoftComplement:
        return c_[i]->region(1 - l, other);
      case RicciArg::CgComplement:
        if (side == Side::Above) {
          if (l <= 0) return Box::unbounded();
          return 1 / l < kCgFloor ? Box() : c_[i]->region(1 / l, other);
        }
        if (l <= 0) return Box();
        return 1 / l <= kCgFloor ? Box::unbounded() : c_[i]->region(1 / l, other);
    }
    return Box::unbounded();
  }

  RicciParams m_;
  double global_L_;
};

enum class SetOp { Union, Intersection, Difference };

NodePtr create_ricci(const Params& p, const BuildContext& ctx, SetOp op) {
  if (ctx.convention == Convention::Zero)
    p.fail("type", "ricci_* applies to soft or constructive objects (docs/math.md §5.3, §5.4)");
  const double n = p.number("n");
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  refuse_negative_strength(p, ctx.kind->name);
  const bool soft = ctx.convention == Convention::Soft;
  const RicciArg rest = op != SetOp::Difference ? RicciArg::Same
                        : soft                  ? RicciArg::SoftComplement
                                                : RicciArg::CgComplement;
  // Soft union and constructive intersection/difference are the q = n means.
  const bool positive = soft ? op == SetOp::Union : op != SetOp::Union;
  return std::make_unique<Ricci>(std::move(c), RicciParams{positive, n, rest});
}

}  // namespace

NodePtr create_ricci_union(const Params& p, const BuildContext& ctx) {
  return create_ricci(p, ctx, SetOp::Union);
}
NodePtr create_ricci_intersection(const Params& p, const BuildContext& ctx) {
  return create_ricci(p, ctx, SetOp::Intersection);
}
NodePtr create_ricci_difference(const Params& p, const BuildContext& ctx) {
  return create_ricci(p, ctx, SetOp::Difference);
}

}  // namespace softtrace

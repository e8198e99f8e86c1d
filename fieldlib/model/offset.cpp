#include "kernels/offset.h"

#include <algorithm>
#include <cmath>

#include "describe/building.h"
#include "model/blends.h"
#include "model/program_builder.h"
#include "model/scaled_node.h"
#include "program/ops/potential_ops.h"

namespace softtrace {

namespace {

// s·(f - c)   — zero-surface function from a distance function, 003 §2.1, docs/scene-format.md
// "offset"
class Offset final : public ScaledNode {
 public:
  Offset(NodePtr child, double s, double c) : ScaledNode(std::move(child), s), c_(c) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const double v = child_->eval(p, grad);
    if (grad) *grad = offset_gradient(s_, *grad);
    return offset_value(s_, c_, v);
  }
  Box region(double level, Side side) const override {
    // The child's side flips with the sign of s; its level c + level/s is rounded away from
    // the side enclosed (up for Below, down for Above) so no point is lost to rounding.
    const Side child_side = (s_ > 0) == (side == Side::Below) ? Side::Below : Side::Above;
    const double t = child_side == Side::Below ? iv::up(c_ + iv::up(level / s_))
                                               : iv::down(c_ + iv::down(level / s_));
    return child_->region(t, child_side);
  }
  // The child's code, then one instruction with s and c inline.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{Op::Offset};
    i.in = b.compile(*child_, reg);
    i.out = b.new_slot();
    i.a = b.consts(OffsetOp::constants(s_, c_));
    return b.emit(i);
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    const NodeBounds f = child_->bounds(b);
    return {offset_interval(s_, c_, f.value), offset_lipschitz(s_, f.lipschitz)};
  }

  double c_;
};

}  // namespace

NodePtr create_offset(const Params& p, const BuildContext& ctx) {
  std::vector<NodePtr> children = build_children(p, "children", ctx);
  const double s = p.number("scale", 1.0);
  p.check(s != 0, "scale", "expected scale != 0 (s = 0 gives a constant field)");
  const double c = p.number("level", 1.0);
  return std::make_unique<Offset>(std::move(children[0]), s, c);
}

}  // namespace softtrace

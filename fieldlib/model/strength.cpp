#include "model/strength.h"

#include <limits>
#include <string>

#include "kernels/strength.h"
#include "model/program_builder.h"
#include "model/scaled_node.h"
#include "program/ops/potential_ops.h"

namespace softtrace {

namespace {

// s·f for a soft object f (f >= 0 everywhere: a potential's value)   — docs/math.md §4.10
class Strength final : public ScaledNode {
 public:
  Strength(NodePtr child, double s) : ScaledNode(std::move(child), s) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const double v = child_->eval(p, grad);
    if (grad) *grad = strength_gradient(s_, *grad);
    return strength_value(s_, v);
  }
  bool polynomial_blob(PolynomialBlob* b) const override {
    if (!child_->polynomial_blob(b)) return false;
    b->c2 *= s_;
    b->c3 *= s_;
    return true;
  }
  // s f >= l ⇔ f >= l/s for s > 0 and f <= l/s for s < 0 (sides swap for <=), the level rounded
  // away from the side enclosed. A negative s over f >= 0: {s f >= l > 0} is empty, and
  // {s f <= l < 0} = {f >= l/s} lies in f's support, which is how a sum finds where a negative
  // term may be dropped (program_builder.cpp).
  Box region(double level, Side side) const override {
    if (s_ < 0 && side == Side::Above && level > 0) return Box();
    const Side child_side = (s_ > 0) == (side == Side::Below) ? Side::Below : Side::Above;
    const double t = child_side == Side::Below ? iv::up(level / s_) : iv::down(level / s_);
    return child_->region(t, child_side);
  }
  // The soft object's code, then one instruction with s inline.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{Op::Strength};
    i.in = b.compile(*child_, reg);
    i.out = b.new_slot();
    i.a = b.consts(StrengthOp::constants(s_));
    return b.emit(i);
  }
  NodePtr clone() const override {
    NodePtr child = child_->clone();
    if (!child) return nullptr;
    return std::make_unique<Strength>(std::move(child), s_);
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    const NodeBounds f = child_->bounds(b);
    return {strength_interval(s_, f.value), strength_lipschitz(s_, f.lipschitz)};
  }
};

// The pointer (relative to p) of the first negative strength under p's children, or "".
std::string negative_strength(const Params& p) {
  const auto& j = p.raw();
  if (j.value("type", "") == "soft_object" && j.contains("strength") &&
      j.at("strength").is_number() && j.at("strength").get<double>() < 0)
    return "strength";
  if (!j.contains("children") || !j.at("children").is_array()) return "";
  const std::vector<Params> kids = p.objects("children");
  for (size_t i = 0; i < kids.size(); ++i) {
    const std::string inner = negative_strength(kids[i]);
    if (!inner.empty()) return "children/" + std::to_string(i) + "/" + inner;
  }
  return "";
}

}  // namespace

NodePtr with_strength(NodePtr child, double s) {
  if (s == 1) return child;
  return std::make_unique<Strength>(std::move(child), s);
}

void refuse_negative_strength(const Params& p, const char* blend) {
  const std::string at = negative_strength(p);
  if (at.empty()) return;
  p.fail(at, std::string("a negative strength cannot enter ") + blend +
                 ", whose formula needs its soft fields in [0, 1] (soft_blend, min, max and "
                 "complement take any strength; docs/scene-format.md \"soft_object\")");
}

}  // namespace softtrace

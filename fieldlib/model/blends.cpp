#include "model/blends.h"

#include <limits>

#include "describe/building.h"
#include "model/nary_node.h"
#include "model/program_builder.h"

namespace softtrace {

namespace {

// Σ f_i   — soft blend B_SUk, 000 Eq. 12, 002 Eq. 3, docs/math.md §5.1
class SoftBlend final : public NaryNode<SoftBlend> {
 public:
  explicit SoftBlend(std::vector<NodePtr> children) : NaryNode(std::move(children)) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    double v = 0;
    if (grad) *grad = {};
    Vec3 g;
    for (const auto& c : c_) {
      v += c->eval(p, grad ? &g : nullptr);
      if (grad) *grad += g;
    }
    return v;
  }
  double lipschitz() const override {
    double L = 0;
    for (const auto& c : c_) L += c->lipschitz();
    return L;
  }
  Box region(double level, Side side) const override {
    if (side == Side::Below || level <= 0) return Box::unbounded();
    // Σ f_i >= level > 0 needs some f_i > 0.
    Box b;
    for (const auto& c : c_) b = b.united(c->region(std::numeric_limits<double>::min(), side));
    return b;
  }
  int compile(ProgramBuilder& b, int reg) const override { return b.nary(Op::Sum, c_, reg); }

 private:
  friend NaryNode;

  // Σ [f_i] and Σ L_i, summed in the children's order.
  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    NodeBounds s{Interval(0), 0};
    for (size_t i = 0; i < c_.size(); ++i) {
      s.value = s.value + I[i];
      s.lipschitz += L[i];
    }
    return s;
  }
};

}  // namespace

NodePtr create_soft_blend(const Params& p, const BuildContext& ctx) {
  return std::make_unique<SoftBlend>(build_children(p, "children", ctx));
}

}  // namespace softtrace

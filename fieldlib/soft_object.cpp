#include "soft_object.h"

#include <cmath>

#include "potentials.h"

namespace softtrace {

namespace {

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
  Interval interval(const Box& b) const override { return P_->interval(d_->interval(b)); }
  double lipschitz() const override { return chain(P_->lipschitz(), d_->lipschitz()); }
  double lipschitz(const Box& b) const override {
    return chain(P_->lipschitz(d_->interval(b)), d_->lipschitz(b));
  }
  Box region(double level, Side side) const override {
    if (side == Side::Above && level > 0) return d_->region(1, Side::Below);
    return Box::unbounded();
  }

 private:
  // A potential that is flat over the box makes the composite flat, whatever d does.
  static double chain(double LP, double Ld) { return LP == 0 ? 0 : LP * Ld; }

  NodePtr d_;
  PotentialPtr P_;
};

}  // namespace

NodePtr create_soft_object(const Params& p, const BuildContext& ctx) {
  NodePtr d = build_field(p.object("distance"), ctx);
  PotentialPtr P = p.has("potential") ? build_potential(p.object("potential")) : make_blanc(0);
  return std::make_unique<SoftObject>(std::move(d), std::move(P));
}

}  // namespace softtrace

// Skeletal line segment r(X)/I_r (docs/math.md §2.8).
#include <algorithm>
#include <cmath>
#include <limits>

#include "distances.h"

namespace softtrace {

namespace {

// Distance to the segment AB divided by the influential radius   — 000 Eq. 5
class Segment final : public FieldNode {
 public:
  Segment(const Vec3& a, const Vec3& b, double radius) : a_(a), ab_(b - a), r_(radius) {
    len2_ = dot(ab_, ab_);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const Vec3 q = p - closest(p);
    const double dist = length(q);
    if (grad) *grad = dist > 0 ? q / (dist * r_) : Vec3{};
    return dist / r_;
  }
  // The distance to a set is 1-Lipschitz, so over a box it is within half a diagonal of the
  // distance at the centre.
  Interval interval(const Box& b) const override {
    const double c = length(b.center() - closest(b.center())), h = 0.5 * b.diagonal();
    return iv::out(std::max(0.0, c - h) / r_, (c + h) / r_);
  }
  double lipschitz() const override { return 1 / r_; }
  // Off the segment |∇f| = 1/r, and the Euclidean distance e has Hessian norm 1/e (its level
  // sets are cylinders and spheres of radius e, joined C^1), so |Hf| <= 1/(r·e_min).
  double gradient_floor(const Box& b) const override {
    return distance_lower(b) > 0 ? iv::down(1 / r_) : 0;
  }
  double hessian_bound(const Box& b) const override {
    const double e = distance_lower(b);
    return e > 0 ? iv::up(1 / iv::down(r_ * e)) : std::numeric_limits<double>::infinity();
  }
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    Box b;
    b.extend(a_);
    b.extend(a_ + ab_);
    const double e = level * r_;
    return {b.lo - Vec3{e, e, e}, b.hi + Vec3{e, e, e}};
  }

 private:
  double distance_lower(const Box& b) const {
    const double c = length(b.center() - closest(b.center())), h = 0.5 * b.diagonal();
    return iv::down(c - iv::up(h * (1 + 1e-12)));
  }
  Vec3 closest(const Vec3& p) const {
    const double t = len2_ > 0 ? std::clamp(dot(p - a_, ab_) / len2_, 0.0, 1.0) : 0.0;
    return a_ + ab_ * t;
  }
  Vec3 a_, ab_;
  double r_, len2_;
};

}  // namespace

NodePtr create_segment(const Params& p, const BuildContext&) {
  return std::make_unique<Segment>(p.vec3("p0"), p.vec3("p1"), p.number("radius"));
}

}  // namespace softtrace

// Skeletal line segment r(X)/I_r (docs/math.md §2.8).
#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/skeletal.h"
#include "model/distances.h"
#include "model/program_builder.h"
#include "program/ops/skeletal_ops.h"

namespace softtrace {

namespace {

// Distance to the segment AB divided by the influential radius   — 000 Eq. 5. The kernels:
// skeletal.h.
class Segment final : public FieldNode {
 public:
  Segment(const Vec3& a, const Vec3& b, double radius) : m_{a, b - a, radius, 0} {
    m_.len2 = dot(m_.ab, m_.ab);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    return line_segment_distance(m_, p, grad);
  }
  // |X - closest(X)|/r is the distance from (X - a)/r to the segment from 0 to ab/r: a capsule.
  bool polynomial_blob(PolynomialBlob* b) const override {
    const double s = 1 / m_.r;
    b->L.r[0] = {s, 0, 0};
    b->L.r[1] = {0, s, 0};
    b->L.r[2] = {0, 0, s};
    b->k = m_.a * -s;
    b->axis = m_.len2 > 0 ? m_.ab * s : Vec3{};
    return true;
  }
  double lipschitz() const override { return 1 / m_.r; }
  // Off the segment |∇f| = 1/r, and the Euclidean distance e has Hessian norm 1/e (its level
  // sets are cylinders and spheres of radius e, joined C^1), so |Hf| <= 1/(r·e_min).
  double gradient_floor(const Box& b) const override {
    return distance_lower(b) > 0 ? iv::down(1 / m_.r) : 0;
  }
  double hessian_bound(const Box& b) const override {
    const double e = distance_lower(b);
    return e > 0 ? iv::up(1 / iv::down(m_.r * e)) : std::numeric_limits<double>::infinity();
  }
  bool hessian(const Vec3& p, Mat3* H) const override { return line_segment_hessian(m_, p, H); }
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    Box b;
    b.extend(m_.a);
    b.extend(m_.a + m_.ab);
    const double e = level * m_.r;
    return {b.lo - Vec3{e, e, e}, b.hi + Vec3{e, e, e}};
  }
  // One instruction with the parameters inline, in LineSegmentOp's layout.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.single(Op::LineSegment, reg, LineSegmentOp::constants(m_));
  }

 private:
  // The distance's range over the box (skeletal.h); the slope is 1/r everywhere off the segment.
  NodeBounds box_bounds(const Box& b) const override {
    return {line_segment_interval(m_, b), lipschitz()};
  }

  double distance_lower(const Box& b) const {
    const double c = length(b.center() - line_segment_closest(m_, b.center())),
                 h = 0.5 * b.diagonal();
    return iv::down(c - iv::up(h * (1 + 1e-12)));
  }
  LineSegmentParams m_;
};

}  // namespace

NodePtr create_segment(const Params& p, const BuildContext&) {
  return std::make_unique<Segment>(p.vec3("p0"), p.vec3("p1"), p.number("radius"));
}

}  // namespace softtrace

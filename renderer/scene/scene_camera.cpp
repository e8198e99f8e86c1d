// The camera's rules and the camera a scene gets without one, framing its objects' finite parts
// (scene.h).
#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/ranges.h"
#include "scene/scene.h"

namespace softtrace {

namespace {

// The widest image (16384 x 1) is 16384 times as wide as high: an orthographic view's plane, or a
// lens's disc, reaches that far from the eye and rays start all over it.
constexpr double kMaxAspect = 16384;

// The half-space {x : dot(normal, x) <= offset} of a plane operand, in its CSG's frame.
struct HalfSpace {
  Vec3 normal;
  double offset;
};

std::optional<HalfSpace> half_space(const SceneObject& o) {
  if (o.csg || !o.shape || o.shape->shape != Primitive::Shape::Plane) return std::nullopt;
  // Inside is dot(n, p) <= d for p = to_object (x - offset): dot(to_object^T n, x - offset) <= d.
  const Primitive& p = *o.shape;
  const Vec3 n = p.to_object.transposed_times(p.normal);
  return HalfSpace{n, p.distance + dot(n, p.to_world.offset)};
}

// The bounding box of box ∩ h (exact but for rounding): along axis i the largest x_i of the
// intersection is where the other coordinates take dot(n, x) at its least over the box (a linear
// programme over a box and one half-space), so each side moves in to (offset - the others' least) /
// n_i or stays.
Box clipped(const Box& box, const HalfSpace& h) {
  double least = 0;  // the least of dot(n, x) over the box
  for (int i = 0; i < 3; ++i) least += std::min(h.normal[i] * box.lo[i], h.normal[i] * box.hi[i]);
  if (!(least <= h.offset)) return Box();  // the box lies wholly outside
  Box b = box;
  for (int i = 0; i < 3; ++i) {
    const double n = h.normal[i];
    if (n == 0) continue;
    const double others = least - std::min(n * box.lo[i], n * box.hi[i]);
    const double edge = (h.offset - others) / n;
    if (n > 0) b.hi[i] = std::min(b.hi[i], edge);
    if (n < 0) b.lo[i] = std::max(b.lo[i], edge);
  }
  return b;
}

}  // namespace

CameraProblem camera_problem(const Camera& c) {
  if (!(max_abs(c.eye) <= kMaxPosition))
    return {"eye", std::string("expected an eye ") + kPositionRule + " (rays start there)"};
  if (!(c.fov > 0 && c.fov < 180))
    return {"fov", "expected a vertical field of view in (0, 180) degrees"};
  if (!(c.aspect == 0 || (c.aspect >= 1 / kMaxAspect && c.aspect <= kMaxAspect)))
    return {"aspect", "expected a view's width / height from 1/16384 to 16384"};
  const Vec3 view = c.target - c.eye;
  if (!(max_abs(view) > 0)) return {"target", "expected a target different from the eye"};
  const double distance = scaled_length(view);
  if (!(distance >= 1 / kMaxDistance && distance <= kMaxDistance))
    return {"target", "expected a target between 1e-150 and 1e150 from the eye"};
  if (!(max_abs(c.up) > 0)) return {"up", "expected a non-zero up vector"};
  if (!(length(cross(unit(view), unit(c.up))) > 1e-9))
    return {"up", "expected an up vector not parallel to the viewing direction"};
  if (c.projection == Camera::Projection::Orthographic) {
    const double half_width = distance * std::tan(0.5 * c.fov * M_PI / 180.0) * kMaxAspect;
    if (!(max_abs(c.eye) + half_width <= kMaxPosition))
      return {"fov", std::string("expected an orthographic view whose plane (2 |target - eye| "
                                 "tan(fov/2) high, up to 16384 times as wide) lies ") +
                         kPositionRule + " (rays start there)"};
  }
  if (!(c.aperture >= 0 && max_abs(c.eye) + c.aperture <= kMaxPosition))
    return {"aperture", std::string("expected an aperture >= 0 whose lens lies ") + kPositionRule +
                            " (rays start there)"};
  if (!(c.focal_distance >= 0 && c.focal_distance <= kMaxDistance))
    return {"focal_distance", "expected a focal distance >= 0 and at most 1e150 (0: the target's)"};
  return {};
}

void normalize_up(Camera& c) {
  c.up = unit(c.up);
}

Camera camera_framing(const Box& box, double aspect) {
  Camera c;
  c.target = box.center();
  // The bounding sphere fills the narrower field of view: vertical fov, or the horizontal one
  // that the aspect gives.
  const double half_v = 0.5 * c.fov * M_PI / 180.0;
  const double half = std::min(half_v, std::atan(std::tan(half_v) * aspect));
  const double radius = std::max(0.5 * scaled_length(box.extent()), 1e-9);
  // From the front right and above, as the figures' scenes look (eye [40, -55, 32] at 0).
  const Vec3 from = unit(Vec3{0.55, -0.75, 0.45});
  c.eye = c.target + from * (radius / std::sin(half));
  return c;
}

std::optional<Box> framing_box(const SceneObject& o) {
  const auto finite = [](const Box& b) {
    return !b.empty() && std::max(max_abs(b.lo), max_abs(b.hi)) < kMaxPosition;
  };
  if (!o.csg) {
    if (o.shape && o.shape->shape == Primitive::Shape::Plane) return std::nullopt;
    return finite(o.bounds) ? std::optional<Box>(o.bounds) : std::nullopt;
  }
  std::optional<Box> inner;
  const auto& operands = o.csg->operands;
  switch (o.csg->op) {
    case Csg::Op::Union:
    case Csg::Op::Merge:
      for (const SceneObject& a : operands)
        if (const std::optional<Box> b = framing_box(a)) inner = inner ? inner->united(*b) : *b;
      break;
    case Csg::Op::Intersection:
      for (const SceneObject& a : operands)
        if (const std::optional<Box> b = framing_box(a))
          inner = inner ? inner->intersected(*b) : *b;
      // A plane operand frames nothing alone but cuts the others' box to its half-space.
      for (const SceneObject& a : operands)
        if (const std::optional<HalfSpace> h = half_space(a); h && inner)
          inner = clipped(*inner, *h);
      break;
    case Csg::Op::Difference:
      inner = framing_box(operands[0]);
      // Taking a plane's solid away leaves the first operand within the other half-space.
      for (size_t k = 1; k < operands.size(); ++k)
        if (const std::optional<HalfSpace> h = half_space(operands[k]); h && inner)
          inner = clipped(*inner, {-h->normal, -h->offset});
      break;
  }
  if (!inner || inner->empty()) return std::nullopt;
  Box box = *inner;
  if (o.csg->placed) {
    box = Box();
    for (int c = 0; c < 8; ++c) box.extend(o.csg->to_parent.apply(inner->corner(c)));
  }
  // The loader's box holds the solid too (an intersection's is the operands' boxes' intersection,
  // a cutting plane's box included): the frame is where both are.
  const Box both = box.intersected(o.bounds);
  return finite(both) ? both : box;
}

}  // namespace softtrace

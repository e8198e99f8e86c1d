#include "scene/primitive_load.h"

#include <cmath>

#include "scene/placement.h"
#include "scene/ranges.h"
#include "scene/scene_keys.h"

namespace softtrace {

namespace {

// The object-space box of a bounded shape.
Box local_box(const Primitive& s) {
  switch (s.shape) {
    case Primitive::Shape::Plane:
      return Box::unbounded();
    case Primitive::Shape::Box:
      return {s.a, s.b};
    case Primitive::Shape::Sphere:
      return Box::around(s.a, s.r0);
    case Primitive::Shape::Cylinder:
    case Primitive::Shape::Cone: {
      const double r = std::max(s.r0, s.r1);
      return Box::around(s.a, r).united(Box::around(s.b, r));
    }
    case Primitive::Shape::Disc:
      return Box::around(s.a, s.r0);
  }
  return Box::unbounded();
}

}  // namespace

const char* shape_name(Primitive::Shape s) {
  switch (s) {
    case Primitive::Shape::Plane:
      return "plane";
    case Primitive::Shape::Box:
      return "box";
    case Primitive::Shape::Sphere:
      return "sphere";
    case Primitive::Shape::Cylinder:
      return "cylinder";
    case Primitive::Shape::Cone:
      return "cone";
    case Primitive::Shape::Disc:
      return "disc";
  }
  return "";
}

std::string place_primitive(Primitive& s, const Affine& m) {
  s.to_world = compose(m, s.to_world);
  if (!invert(s.to_world.linear, s.to_object))
    return "expected an invertible placement (scale and matrix)";
  const auto identity = [](const Mat3& m) {
    const Mat3 one;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (!(m.r[r][c] == one.r[r][c])) return false;
    return true;
  };
  s.unplaced =
      identity(s.to_world.linear) && identity(s.to_object) && max_abs(s.to_world.offset) == 0;
  // As the tracer turns any normal to the world: by the inverse transpose, then unit.
  const Vec3 w = s.to_object.transposed_times(s.normal);
  const double l = length(w);
  s.world_normal = l > 0 ? w / l : w;
  const Box local = local_box(s);
  if (local.bounded()) {
    s.world_box = Box();
    for (int c = 0; c < 8; ++c) s.world_box.extend(s.to_world.apply(local.corner(c)));
    if (!(std::max(max_abs(s.world_box.lo), max_abs(s.world_box.hi)) <= kMaxPosition))
      return std::string("expected a placed shape ") + kPositionRule;
  } else {
    s.world_box = Box({-kMaxPosition, -kMaxPosition, -kMaxPosition},
                      {kMaxPosition, kMaxPosition, kMaxPosition});
  }
  return "";
}

Primitive load_primitive(const Params& p) {
  static const std::vector<std::string> any_shape = [] {
    std::vector<std::string> all;
    for (const char* type : {"plane", "box", "sphere", "cylinder", "cone", "disc"})
      for (const std::string& key : scene_keys(std::string("shape: ") + type))
        if (std::find(all.begin(), all.end(), key) == all.end()) all.push_back(key);
    return all;
  }();
  p.check_keys(any_shape);
  Primitive s;
  const std::string type = p.string("type");
  bool known = false;
  for (const auto shape :
       {Primitive::Shape::Plane, Primitive::Shape::Box, Primitive::Shape::Sphere,
        Primitive::Shape::Cylinder, Primitive::Shape::Cone, Primitive::Shape::Disc})
    if (type == shape_name(shape)) {
      s.shape = shape;
      known = true;
    }
  if (!known)
    p.fail("type",
           "unknown shape '" + type + "' (expected plane, box, sphere, cylinder, cone or disc)");
  p.check_keys(scene_keys("shape: " + type), " for a " + type);
  const auto length_ok = [&](const std::string& key, double v, bool zero_ok) {
    p.check((zero_ok ? v >= 0 : v > 0) && v <= kMaxPosition, key,
            std::string("expected a length ") + (zero_ok ? ">= 0" : "> 0") + " and at most 1e12");
  };
  const auto point = [&](const std::string& key, const Vec3& fallback) {
    const Vec3 v = p.vec3(key, fallback);
    p.check(max_abs(v) <= kMaxPosition, key, std::string("expected a point ") + kPositionRule);
    return v;
  };
  const auto direction = [&](const std::string& key) {
    const Vec3 v = p.vec3(key, {0, 0, 1});
    p.check(max_abs(v) > 0, key, "expected a non-zero normal");
    return unit(v);
  };
  switch (s.shape) {
    case Primitive::Shape::Plane:
      s.normal = direction("normal");
      s.distance = p.number("distance", 0);
      p.check(std::abs(s.distance) <= kMaxPosition, "distance",
              "expected a distance from the origin of at most 1e12");
      break;
    case Primitive::Shape::Box: {
      const Vec3 c1 = point("corner1", {-1, -1, -1}), c2 = point("corner2", {1, 1, 1});
      for (int i = 0; i < 3; ++i) {
        s.a[i] = std::min(c1[i], c2[i]);
        s.b[i] = std::max(c1[i], c2[i]);
        p.check(s.a[i] < s.b[i], "corner2", "expected corners that differ in every coordinate");
      }
      break;
    }
    case Primitive::Shape::Sphere:
      s.a = point("center", {0, 0, 0});
      s.r0 = p.number("radius", 1);
      length_ok("radius", s.r0, false);
      break;
    case Primitive::Shape::Cylinder:
    case Primitive::Shape::Cone:
      s.a = point("base", {0, 0, 0});
      s.b = point("cap", {0, 0, 1});
      p.check(max_abs(s.b - s.a) > 0, "cap", "expected a cap different from the base");
      if (s.shape == Primitive::Shape::Cylinder) {
        s.r0 = s.r1 = p.number("radius", 1);
        length_ok("radius", s.r0, false);
      } else {
        s.r0 = p.number("base_radius", 1);
        s.r1 = p.number("cap_radius", 0);
        length_ok("base_radius", s.r0, true);
        length_ok("cap_radius", s.r1, true);
        p.check(s.r0 > 0 || s.r1 > 0, "base_radius", "expected a radius > 0 at one end");
      }
      break;
    case Primitive::Shape::Disc:
      s.a = point("center", {0, 0, 0});
      s.normal = direction("normal");
      s.r0 = p.number("radius", 1);
      length_ok("radius", s.r0, false);
      s.hole = p.number("hole_radius", 0);
      p.check(s.hole >= 0 && s.hole < s.r0, "hole_radius",
              "expected a hole radius >= 0 and below the radius");
      break;
  }
  const std::string problem = place_primitive(s, load_placement(p));
  p.check(problem.empty(), "", problem);
  p.finish();
  return s;
}

}  // namespace softtrace

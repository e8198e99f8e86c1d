#include "scene/primitive_load.h"

#include <cmath>

#include "scene/ranges.h"
#include "scene/scene_keys.h"

namespace softtrace {

namespace {

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.r[i][j] = a.r[i].x * b.r[0][j] + a.r[i].y * b.r[1][j] + a.r[i].z * b.r[2][j];
  return m;
}

// The inverse by cofactors; `det` returns the determinant (0 for a singular map).
Mat3 inverse(const Mat3& m, double& det) {
  const Vec3 &x = m.r[0], &y = m.r[1], &z = m.r[2];
  const Vec3 c0 = cross(y, z), c1 = cross(z, x), c2 = cross(x, y);
  det = dot(x, c0);
  Mat3 inv;
  for (int i = 0; i < 3; ++i) inv.r[i] = Vec3{c0[i], c1[i], c2[i]} / det;
  return inv;
}

// Scale, then rotate, then translate, then `matrix` (3 rows [a, b, c, tx]), as the soft objects'
// placement keys read.
Affine load_placement(const Params& p) {
  Affine m;
  if (p.has("scale")) {
    const Vec3 s = p.vec3("scale");
    for (int i = 0; i < 3; ++i)
      p.check(std::abs(s[i]) >= 1e-12 && std::abs(s[i]) <= 1e12, "scale/" + std::to_string(i),
              "expected a scale factor of magnitude between 1e-12 and 1e12");
    m.linear = Mat3{{{s.x, 0, 0}, {0, s.y, 0}, {0, 0, s.z}}};
  }
  if (p.has("rotate")) {
    const Params r = p.object("rotate");
    r.check_keys({"axis", "deg"});
    const Vec3 axis = r.vec3("axis");
    r.check(max_abs(axis) > 0, "axis", "expected a non-zero axis");
    const double deg = r.number("deg");
    r.finish();
    m.linear = multiply(Mat3::rotation(unit(axis), deg), m.linear);
  }
  if (p.has("translate")) {
    m.offset = p.vec3("translate");
    p.check(max_abs(m.offset) <= kMaxPosition, "translate",
            std::string("expected a translation ") + kPositionRule);
  }
  if (p.has("matrix")) {
    const nlohmann::json& rows = p.get("matrix");
    const auto ok = [&] {
      if (!rows.is_array() || rows.size() != 3) return false;
      for (const auto& row : rows) {
        if (!row.is_array() || row.size() != 4) return false;
        for (const auto& v : row)
          if (!v.is_number() || !(std::abs(v.get<double>()) <= 1e12)) return false;
      }
      return true;
    };
    if (!ok()) p.fail("matrix", "expected 3 rows [a, b, c, t] of numbers within 1e12");
    Mat3 l;
    Vec3 t;
    for (int i = 0; i < 3; ++i) {
      l.r[i] = {rows[i][0].get<double>(), rows[i][1].get<double>(), rows[i][2].get<double>()};
      t[i] = rows[i][3].get<double>();
    }
    m.linear = multiply(l, m.linear);
    m.offset = l * m.offset + t;
  }
  return m;
}

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
  s.to_world = load_placement(p);
  double det = 0;
  s.to_object = inverse(s.to_world.linear, det);
  p.check(std::isfinite(det) && std::abs(det) > 1e-30 && max_abs(s.to_object.r[0]) < 1e30 &&
              max_abs(s.to_object.r[1]) < 1e30 && max_abs(s.to_object.r[2]) < 1e30,
          "", "expected an invertible placement (scale and matrix)");
  const Box local = local_box(s);
  if (local.bounded()) {
    for (int c = 0; c < 8; ++c) s.world_box.extend(s.to_world.apply(local.corner(c)));
    p.check(std::max(max_abs(s.world_box.lo), max_abs(s.world_box.hi)) <= kMaxPosition, "",
            std::string("expected a placed shape ") + kPositionRule);
  } else {
    s.world_box = Box({-kMaxPosition, -kMaxPosition, -kMaxPosition},
                      {kMaxPosition, kMaxPosition, kMaxPosition});
  }
  p.finish();
  return s;
}

}  // namespace softtrace

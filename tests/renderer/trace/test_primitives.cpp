// Plain primitives (scene/primitive.h, trace/primitive_trace.h): the span a ray spends inside each
// placed shape against an independent point-membership test, normals against the surface, the
// infinite plane's reach, the loader's refusals and a rendered shadow.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "render/camera.h"
#include "render/frame.h"
#include "render/shading.h"
#include "scene/primitive_load.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"
#include "trace/primitive_trace.h"

namespace softtrace {
namespace {

// Whether the world point p is inside the shape, from its definition in the shape's own space.
bool inside(const Primitive& s, const Vec3& world) {
  const Vec3 p = s.to_object * (world - s.to_world.offset);
  switch (s.shape) {
    case Primitive::Shape::Plane:
      return dot(s.normal, p) <= s.distance;
    case Primitive::Shape::Box:
      return Box(s.a, s.b).contains(p);
    case Primitive::Shape::Sphere:
      return length(p - s.a) <= s.r0;
    case Primitive::Shape::Cylinder:
    case Primitive::Shape::Cone: {
      const double h = length(s.b - s.a);
      const Vec3 u = (s.b - s.a) / h;
      const double along = dot(p - s.a, u);
      const double across = length(p - s.a - u * along);
      return along >= 0 && along <= h && across <= s.r0 + (s.r1 - s.r0) * along / h;
    }
    case Primitive::Shape::Disc:
      return false;
  }
  return false;
}

Primitive shape_from(const std::string& json) {
  const nlohmann::json j = nlohmann::json::parse(json);
  return load_primitive(Params(j, "/shape", std::make_shared<const std::string>("t.json")));
}

// The unplaced plane takes first_hit's and occludes' own way (its normal from
// Primitive::world_normal); the span below still turns its normal to the world on each call.
const std::string kUnplacedPlane =
    R"({"type": "plane", "normal": [0.3, -0.2, 1], "distance": 0.5})";

const std::vector<std::string> kSolids = {
    R"({"type": "plane", "normal": [0.3, -0.2, 1], "distance": 0.5, "rotate": {"axis": [1, 0, 0], "deg": 20}})",
    kUnplacedPlane,
    R"({"type": "box", "corner1": [-1, -2, -0.5], "corner2": [2, 1, 1.5], "scale": [1, 0.5, 2],
        "rotate": {"axis": [1, 1, 0], "deg": 33}, "translate": [0.2, 0, -0.3]})",
    R"({"type": "sphere", "center": [0.5, 0, 0], "radius": 1.7, "scale": [2, 1, 0.7]})",
    R"({"type": "cylinder", "base": [0, 0, -1], "cap": [0.5, 0.3, 1.5], "radius": 0.8,
        "matrix": [[1, 0.2, 0, 0.1], [0, 1, 0.1, 0], [0.1, 0, 1.3, -0.2]]})",
    R"({"type": "cone", "base": [0, 0, -1], "base_radius": 1.5, "cap": [0, 0.4, 1.5], "cap_radius": 0.2,
        "rotate": {"axis": [0, 1, 0], "deg": -40}})",
    R"({"type": "cone", "base": [0, 0, 1], "base_radius": 0, "cap": [0, 0, -1], "cap_radius": 1.2})",
};

// Along random rays through the shape's neighbourhood, a point is inside exactly where the span
// says (away from its ends by a hair), and each end's normal points out of the solid.
TEST(Primitives, SpansAgreeWithPointMembershipAndNormalsPointOut) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const std::string& json : kSolids) {
    const Primitive s = shape_from(json);
    int rays_hit = 0, points = 0, normals = 0, answers = 0;
    for (int k = 0; k < 400; ++k) {
      const Vec3 o{6 * u(rng), 6 * u(rng), 6 * u(rng)};
      const Vec3 target{1.5 * u(rng), 1.5 * u(rng), 1.5 * u(rng)};
      const Ray ray{o, normalize(target - o)};
      const SolidSpan span = solid_span(s, ray);
      for (int i = 0; i <= 400; ++i) {
        const double t = -4 + 20.0 * i / 400;
        if (!span.empty() && (std::abs(t - span.t0) < 1e-9 || std::abs(t - span.t1) < 1e-9))
          continue;
        const bool in_span = !span.empty() && t >= span.t0 && t <= span.t1;
        ASSERT_EQ(inside(s, ray.o + ray.d * t), in_span) << json << " ray " << k << " t " << t;
        ++points;
      }
      // A shadow ray's question (no normal) has first_hit's answer, and first_hit the span's end.
      for (const auto& [tnear, tfar] :
           {std::pair{0.0, 1e9}, std::pair{2.0, 9.0}, std::pair{-3.0, 1.0}}) {
        const PrimitiveHit h = first_hit(s, ray, tnear, tfar);
        ASSERT_EQ(occludes(s, ray, tnear, tfar), h.hit) << json << " ray " << k;
        if (!h.hit) continue;
        const Vec3 n = h.t == span.t0 ? span.n0 : span.n1;
        EXPECT_TRUE(h.t == span.t0 || h.t == span.t1) << json << " ray " << k;
        EXPECT_EQ(h.normal.x, n.x);
        EXPECT_EQ(h.normal.y, n.y);
        EXPECT_EQ(h.normal.z, n.z);
        ++answers;
      }
      if (span.empty()) continue;
      ++rays_hit;
      for (const auto& [t, n] : {std::pair{span.t0, span.n0}, std::pair{span.t1, span.n1}}) {
        if (!std::isfinite(t)) continue;
        const Vec3 p = ray.o + ray.d * t;
        EXPECT_NEAR(length(n), 1, 1e-12);
        EXPECT_TRUE(inside(s, p - n * 1e-6)) << json;
        EXPECT_FALSE(inside(s, p + n * 1e-6)) << json;
        ++normals;
      }
    }
    EXPECT_GT(rays_hit, 40) << json;
    EXPECT_GT(points, 100000) << json;
    EXPECT_GT(normals, 40) << json;
    EXPECT_GT(answers, 40) << json;
  }
}

// The tilted plane without placement is one the tracer takes as unplaced (so the test above
// compares its own way's normals with the span's), and its hits' normal is its unit normal.
TEST(Primitives, AnUnplacedPlaneHitsWithItsUnitNormal) {
  const Primitive s = shape_from(kUnplacedPlane);
  ASSERT_TRUE(s.unplaced);
  const Ray down{{0.1, 0.2, 5}, normalize(Vec3{0.1, -0.3, -1})};
  const PrimitiveHit h = first_hit(s, down, 0, 1e9);
  ASSERT_TRUE(h.hit);
  const Vec3 n = normalize(Vec3{0.3, -0.2, 1});
  EXPECT_NEAR(h.normal.x, n.x, 1e-15);
  EXPECT_NEAR(h.normal.y, n.y, 1e-15);
  EXPECT_NEAR(h.normal.z, n.z, 1e-15);
  EXPECT_NEAR(dot(n, down.o + down.d * h.t), 0.5, 1e-12);  // the plane dot(n, p) = distance
}

// A camera beam's rays skip the floor point's max_abs where BeamClear::reach vouches for it:
// unplaced_plane_end_within gives unplaced_plane_end's answer to the bit, also for eyes far out
// and planes crossed near and beyond kMaxPosition, where the point's test decides; so does it with
// the eye's gap given (unplaced_plane_gap, once for the eye's rays).
TEST(Primitives, AnUnplacedPlaneWithinReachAnswersAsWithout) {
  const double kNaN = std::numeric_limits<double>::quiet_NaN();  // the gap taken per ray
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int vouched = 0, beyond = 0;
  for (const double far : {0.0, 1e3, 1e11, 2.4e11, 3e11}) {
    const Vec3 eye{far, -0.5 * far, 2};
    const double reach = BeamClear::reach_from(eye);
    EXPECT_EQ(reach<0, far> kMaxPosition / 4) << far;
    for (int k = 0; k < 4000; ++k) {
      const Vec3 d = normalize(Vec3{u(rng), u(rng), u(rng)});
      // A plane crossed at about 10^[0, 12.3] along the ray, in front or behind, or in front
      // in [0, 1.2 kMaxPosition], where far eyes' points leave kMaxPosition.
      const double t = k % 2 ? std::pow(10.0, 12.3 * (0.5 + 0.5 * u(rng))) * (u(rng) < 0.8 ? 1 : -1)
                             : 0.6 * kMaxPosition * (1 + u(rng));
      const Vec3 n = normalize(Vec3{u(rng), u(rng), u(rng)});
      Primitive s = shape_from(kUnplacedPlane);
      s.normal = n;
      s.distance = dot(n, eye + d * t);
      const Ray ray{eye, d};
      const double inf = std::numeric_limits<double>::infinity();
      const double a = unplaced_plane_end(s, ray, 0, inf);
      const double b = unplaced_plane_end_within(s, ray, 0, inf, reach, kNaN);
      // With the eye's gap taken once for its rays (BeamClear::floor_gap): the same answer.
      const double c = unplaced_plane_end_within(s, ray, 0, inf, reach, unplaced_plane_gap(s, eye));
      ASSERT_EQ(std::isnan(a), std::isnan(b)) << far << " " << t;
      ASSERT_EQ(std::isnan(a), std::isnan(c)) << far << " " << t;
      if (!std::isnan(a)) {
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << far << " " << t;
        EXPECT_EQ(std::memcmp(&a, &c, sizeof a), 0) << far << " " << t;
      }
      vouched += !std::isnan(b) && std::abs(b) <= reach;
      beyond += std::isnan(a) && t > 0 && std::abs(t) <= kMaxPosition;
    }
  }
  EXPECT_GT(vouched, 4000);  // the shortcut was taken
  EXPECT_GT(beyond, 40);     // and points past kMaxPosition were refused
}

TEST(Primitives, DiscHitsLieOnTheRing) {
  const Primitive s = shape_from(
      R"({"type": "disc", "center": [1, 0, 0], "normal": [0, 1, 1], "radius": 2, "hole_radius": 0.5})");
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, misses = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 o{5 * u(rng), 5 * u(rng), 5 * u(rng)};
    const Ray ray{o, normalize(Vec3{1 + 2.5 * u(rng), 2.5 * u(rng), 2.5 * u(rng)} - o)};
    const PrimitiveHit h = first_hit(s, ray, 0, 1e9);
    const double nd = dot(normalize(Vec3{0, 1, 1}), ray.d);
    const double t = dot(normalize(Vec3{0, 1, 1}), Vec3{1, 0, 0} - o) / nd;
    const Vec3 p = o + ray.d * t, w = p - Vec3{1, 0, 0};
    const bool ring = t > 0 && length(w) <= 2 && length(w) >= 0.5;
    if (std::abs(length(w) - 2) < 1e-9 || std::abs(length(w) - 0.5) < 1e-9) continue;
    ASSERT_EQ(h.hit, ring) << k;
    if (h.hit) {
      EXPECT_NEAR(h.t, t, 1e-9 * std::abs(t));
      ++hits;
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
}

// An infinite plane is drawn out to 1e12: a ray that would meet it farther away sees nothing
// (no edge: that far, the plane is within a pixel of the horizon), and no hit lies beyond.
TEST(Primitives, ThePlaneEndsWhereRaysMayStart) {
  const Primitive floor = shape_from(R"({"type": "plane"})");
  const Vec3 eye{0, 0, 2};
  int checked = 0;
  for (const double drop : {1e-3, 1e-9, 1e-11, 1e-13, 1e-15}) {
    const Ray ray{eye, normalize(Vec3{1, 0, -drop})};
    const PrimitiveHit h = first_hit(floor, ray, 0, std::numeric_limits<double>::infinity());
    const double t = 2 / drop;
    EXPECT_EQ(h.hit, t <= 1e12) << drop;
    if (h.hit) {
      EXPECT_LE(max_abs(ray.o + ray.d * h.t), 1e12);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 5);
}

TEST(Primitives, TheLoaderRefusesBadShapesAtTheirPointers) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"type": "torus"})", "/objects/0/shape/type: unknown shape 'torus'"},
      {R"({"type": "sphere", "radius": 0})", "/objects/0/shape/radius: expected a length > 0"},
      {R"({"type": "sphere", "scale": [1, 0, 1]})", "/objects/0/shape/scale/1: expected a scale"},
      {R"({"type": "box", "corner1": [0, 0, 0], "corner2": [1, 0, 1]})",
       "/objects/0/shape/corner2: expected corners that differ"},
      {R"({"type": "cylinder", "cap": [0, 0, 0]})",
       "/objects/0/shape/cap: expected a cap different"},
      {R"({"type": "disc", "hole_radius": 1})", "/objects/0/shape/hole_radius"},
      {R"({"type": "sphere", "matrix": [[1, 0, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0]]})",
       "/objects/0/shape: expected an invertible placement"},
      {R"({"type": "sphere", "translate": [2e12, 0, 0]})", "/objects/0/shape/translate"},
      {R"({"type": "plane", "radius": 1})", "/objects/0/shape/radius: unknown key 'radius'"},
  };
  for (const auto& [shape, expected] : cases) {
    try {
      parse_scene(R"({"objects": [{"shape": )" + shape + "}]}", "bad.json");
      ADD_FAILURE() << shape << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  try {
    parse_scene(R"({"objects": [{"iso": 0.3, "shape": {"type": "sphere"}}]})", "bad.json");
    ADD_FAILURE() << "iso on a shape was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/0/iso: an object with a 'shape' has no 'iso'"),
              std::string::npos)
        << e.what();
  }
  try {
    parse_scene(R"({"objects": [{"shape": {"type": "plane"}}]})", "bad.json");
    ADD_FAILURE() << "a scene of one plane and no camera was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/camera: expected a camera"), std::string::npos)
        << e.what();
  }
}

// A sphere on a floor under a light from straight above: the floor is dark under the sphere and
// lit beside it; the sphere's top is lit, and the floor meets the sphere's silhouette.
TEST(Primitives, ShadowsFallOnTheFloor) {
  const Scene scene = parse_scene(R"({
    "camera": {"eye": [0, -30, 30], "target": [0, 0, 0], "fov": 40},
    "image": {"width": 64, "height": 64},
    "lights": [{"type": "directional", "direction": [0, 0, -1]}],
    "objects": [{"shape": {"type": "plane"}},
                {"shape": {"type": "sphere", "center": [0, 0, 4], "radius": 3}}]})",
                                  "shadow.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  const ViewCamera camera(scene.camera, 64, 64);
  RayWork shadow;
  const auto look = [&](const Vec3& at) {
    const Vec3 d = normalize(at - scene.camera.eye);
    const Ray ray{scene.camera.eye, d, 0, 0};
    const TraceHit h = rt.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(h.hit);
    return std::pair{h, shade(scene, rt.tracers, rt.embree, ray, h, shadow).color};
  };
  const auto [under_hit, under] = look({0, -2.9, 0});  // before the sphere's foot, in its shadow
  const auto [beside_hit, beside] = look({6, 0, 0});
  const auto [top_hit, top] = look({0, 0, 7});
  EXPECT_EQ(under_hit.object, 0);
  EXPECT_EQ(beside_hit.object, 0);
  EXPECT_EQ(top_hit.object, 1);
  EXPECT_EQ(under.x, 0);  // no ambient light: fully shadowed
  EXPECT_NEAR(beside.x, 0.8, 1e-12);
  EXPECT_GT(top.x, 0.7);
  EXPECT_GT(shadow.rays, 0);
}

}  // namespace
}  // namespace softtrace

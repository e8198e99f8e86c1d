// Scenes the direct paths trace (EmbreeScene: one field, alone or with a few primitives) build no
// Embree scene when no ray can start inside a solid, and answer every ray as the Embree scene
// over the same tracers does: camera rays, shadow rays towards a light, and rays from anywhere.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "render/frame.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

// Two murakami blobs, then `extra` objects (JSON, each with a leading comma).
std::string direct_scene(const std::string& material, const std::string& extra) {
  return R"({"camera": {"eye": [0, -30, 8], "target": [0, 0, 0]},
    "lights": [{"type": "point", "position": [10, -10, 20]}],
    "objects": [{"material": )" +
         material + R"(, "field": {"type": "soft_blend", "children": [
      {"type": "soft_object", "potential": {"type": "murakami"},
       "distance": {"type": "lp_metric", "radii": [4, 4, 4], "n": 2}},
      {"type": "soft_object", "potential": {"type": "murakami"}, "translate": [3, 0, 1],
       "distance": {"type": "lp_metric", "radii": [3, 3, 3], "n": 2}}]}})" +
         extra + "]}";
}

const char* kOpaque = R"({"color": [0.8, 0.7, 0.6]})";
const char* kGlass = R"({"transmit": 0.9, "ior": 1.5})";
const char* kFloor = R"(, {"shape": {"type": "plane", "distance": -4}})";
const char* kBall = R"(, {"shape": {"type": "sphere", "center": [-6, 0, 0], "radius": 1.5}})";
const char* kOtherField = R"(, {"field": {"type": "soft_object", "potential": {"type": "murakami"},
    "translate": [9, 0, 0], "distance": {"type": "lp_metric", "radii": [2, 2, 2], "n": 2}}})";

bool builds_embree(const std::string& text) {
  const Scene scene = parse_scene(text, "direct.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  return rt.embree.built();
}

TEST(DirectScenes, BuildNoEmbreeSceneUnlessARayMayStartInside) {
  EXPECT_FALSE(builds_embree(direct_scene(kOpaque, "")));
  EXPECT_FALSE(builds_embree(direct_scene(kOpaque, kFloor)));
  EXPECT_FALSE(builds_embree(direct_scene(kOpaque, std::string(kFloor) + kBall)));
  // Transparent: its transmitted and shadow rays start inside the blobs' solid, which Embree's
  // callbacks trace.
  EXPECT_TRUE(builds_embree(direct_scene(kGlass, "")));
  EXPECT_TRUE(builds_embree(direct_scene(kGlass, kFloor)));
  // Two fields: Embree's boxes choose between them.
  EXPECT_TRUE(builds_embree(direct_scene(kOpaque, kOtherField)));
}

bool same_hit(const TraceHit& a, const TraceHit& b) {
  return a.hit == b.hit && a.object == b.object && a.on_box_face == b.on_box_face &&
         std::memcmp(&a.t, &b.t, sizeof a.t) == 0 && a.normal.x == b.normal.x &&
         a.normal.y == b.normal.y && a.normal.z == b.normal.z;
}

// The scene without Embree against an Embree scene over the same tracers, ray by ray.
void expect_answers_as_embree(const std::string& text) {
  const Scene scene = parse_scene(text, "direct.json");
  const std::vector<TracedObject> objects = traced_objects(scene);
  const SceneTracers tracers(objects, LipschitzMode::Local);
  const EmbreeScene direct(tracers, /*interiors=*/false), embree(tracers, /*interiors=*/true);
  ASSERT_FALSE(direct.built());
  ASSERT_TRUE(embree.built());
  const Vec3 light = scene.lights.at(0).position;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const double inf = std::numeric_limits<double>::infinity();
  int hits = 0, shadowed = 0;
  for (int i = 0; i < 400; ++i) {
    // Camera rays over the blobs and around them, then rays from random points.
    const Vec3 eye = i < 200 ? scene.camera.eye : Vec3{12 * u(rng), 12 * u(rng), 12 * u(rng)};
    const Vec3 at{5 * u(rng), 3 * u(rng), 3 * u(rng)};
    const Ray ray{eye, normalize(at - eye), 0, 1e-6};
    const TraceHit a = direct.intersect(ray, 0, inf), b = embree.intersect(ray, 0, inf);
    ASSERT_TRUE(same_hit(a, b)) << i;
    if (!a.hit) continue;
    ++hits;
    // The shadow ray from the hit towards the light.
    const Vec3 p = ray.o + ray.d * (a.t * (1 - 1e-9));
    const Vec3 to = light - p;
    const Ray shadow{p, normalize(to), 0, 1e-6};
    TraceCounters wa, wb;
    const bool oa = direct.occluded(shadow, 1e-6, length(to), wa);
    ASSERT_EQ(oa, embree.occluded(shadow, 1e-6, length(to), wb)) << i;
    shadowed += oa;
  }
  EXPECT_GT(hits, 150);
  EXPECT_GT(shadowed, 0);
}

TEST(DirectScenes, AnswerEveryRayAsTheEmbreeSceneDoes) {
  expect_answers_as_embree(direct_scene(kOpaque, ""));
  expect_answers_as_embree(direct_scene(kOpaque, std::string(kFloor) + kBall));
}

}  // namespace
}  // namespace softtrace

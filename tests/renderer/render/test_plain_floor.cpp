// The frame shades a camera hit on a plain floor (an unplaced plane beside one blob sum) with
// PlainFloor: its normal and each directional and ambient light's terms taken once for the frame,
// and a clear list's shadow ray answered by the plane's test inline. It must give
// shade_plain_hit's colour, normal, albedo and counters to the bit (test_shade_plain.cpp holds
// shade_plain_hit to shade()). The floor is seen from above and from below (the normal facing
// either way), under an ambient light, a directional light with shadows from above, one from below
// (no light on the upper side), one without shadows, and a point light; with a phong and a
// specular highlight, and matte; and matte without the point light, where a point's colour is
// looked up by its blocked shadow rays (PlainFloor::lean). The shadow lists are ShadowBeams' own
// for each 2x2 block of floor pixels: some clear (beside the cloud), some not (under it).
// A lean floor's point whose shadow rays all miss the cloud's box is shaded with no list
// (PlainFloor::unlisted_colour) and the frame writes its pixel as it traces it (frame.cpp's
// floor_pixel): the same colour and counters as with its lists, and the same film as the frame
// whose pixels all take records (one with anti-aliasing that refines nothing), but for the steps
// (its point is then no list's, and the other points' lists are narrower).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "render/camera.h"
#include "render/frame.h"
#include "render/plain_floor.h"
#include "render/shading.h"
#include "render/shadow_beams.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

// Seven small balls inside the large one, so that the sum has more blobs than
// ShadowBeams::kFewBlobs and takes shadow lists (a sum of fewer walks its shadow rays whole).
std::string small_balls() {
  std::string balls;
  for (int i = 0; i < 7; ++i)
    balls += R"(, { "type": "soft_object", "potential": { "type": "murakami" }, "translate": [)" +
             std::to_string(i - 3) +
             R"(, 0, 3], "distance": { "type": "lp_metric", "radii": [0.5, 0.5, 0.5], "n": 2 } })";
  return balls;
}

std::string floor_scene_json(const char* eye, const char* finish, bool point = true) {
  return std::string(R"({
  "camera": { "eye": )") +
         eye + R"(, "target": [0, 0, 0], "fov": 50 },
  "lights": [
    { "type": "ambient", "intensity": 0.2 },
    { "type": "directional", "direction": [0.5, 0.3, -1], "intensity": 0.7 },
    { "type": "directional", "direction": [-0.2, 0.4, 1], "intensity": 0.3 },
    { "type": "directional", "direction": [0.1, -0.6, -1], "intensity": 0.2, "shadows": false })" +
         std::string(point ? R"(,
    { "type": "point", "position": [-8, -6, 14], "intensity": 0.4 })"
                           : "") +
         R"(
  ],
  "objects": [
    { "material": )" +
         finish + R"(,
      "shape": { "type": "plane", "normal": [0, 0, 1], "distance": -2 } },
    { "material": { "color": [0.85, 0.45, 0.35] }, "convention": "soft", "iso": 0.5,
      "field": { "type": "soft_blend", "children": [
        { "type": "soft_object", "potential": { "type": "murakami" }, "translate": [0, 0, 3],
          "distance": { "type": "lp_metric", "radii": [5, 5, 5], "n": 2 } },
        { "type": "soft_object", "potential": { "type": "murakami" }, "translate": [4, 2, 5],
          "distance": { "type": "lp_metric", "radii": [4, 4, 4], "n": 2 } })" +
         small_balls() + R"( ] } }
  ]
})";
}

bool floor_bits_equal(const Vec3& a, const Vec3& b) {
  return std::memcmp(&a, &b, sizeof(Vec3)) == 0;
}

const char* const kFloorShiny = R"({ "color": [0.62, 0.6, 0.55], "specular": 0.3, "roughness": 0.05,
                                 "phong": 0.4, "brilliance": 1.5 })";
const char* const kFloorMatte = R"({ "color": [0.62, 0.6, 0.55] })";

struct FloorCounts {
  int clear = 0, listed = 0, lit = 0, below = 0;
  int unlisted = 0, declined = 0;  // unlisted_colour's answers and refusals
};

// Every floor pixel of a 64x48 frame, a 2x2 block at a time with its lists, both ways.
FloorCounts check_floor(const char* eye, const char* finish, bool point = true) {
  const Scene scene = parse_scene(floor_scene_json(eye, finish, point), "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  const PlainFloor floor(scene, rt.embree);
  EXPECT_EQ(floor.object(), 0);
  // The colour looked up only without highlights and without the point light.
  EXPECT_EQ(floor.lean(), !point && std::strcmp(finish, kFloorMatte) == 0) << finish;
  const ShadowBeams beams(scene, rt.tracers);
  EXPECT_TRUE(beams.active());
  const int width = 64, height = 48;
  const ViewCamera camera(scene.camera, width, height);
  const SceneObject& obj = scene.objects[0];
  FloorCounts n;
  for (int by = 0; by < height; by += 2)
    for (int bx = 0; bx < width; bx += 2) {
      std::vector<Ray> rays;
      std::vector<TraceHit> hits;
      std::vector<ShadowBeams::Point> points;
      for (int y = by; y < by + 2; ++y)
        for (int x = bx; x < bx + 2; ++x) {
          const Ray ray = camera.generate(x + 0.5, y + 0.5);
          const TraceHit hit = rt.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
          if (!hit.hit || hit.object != 0) continue;
          const Vec3 p = ray.o + ray.d * hit.t;
          rays.push_back(ray);
          hits.push_back(hit);
          points.push_back({p, ray_offset(obj, p, ray.cone_at(hit.t))});
        }
      if (points.empty()) continue;
      // The points as a tile's first block: the tile's, its quarter's and its block's lists are
      // all of them.
      ShadowBeams::Lists lists;
      int starts[17] = {0};
      std::fill(starts + 1, starts + 17, int(points.size()));
      ShadowListsOnDemand view(beams, points.data(), starts, lists);
      view.block(0);
      for (size_t i = 0; i < points.size(); ++i) {
        view.at(points[i]);
        RayWork plain_way, floor_way;
        const Shaded a = shade_plain_hit(scene, rt.tracers, rt.embree, rays[i], hits[i],
                                         obj.material, plain_way, nullptr, view);
        const Shaded b = floor.shade(scene, rt.embree, rays[i], hits[i], floor_way, nullptr, view);
        EXPECT_TRUE(floor_bits_equal(a.color, b.color))
            << eye << " " << bx << "," << by << " " << i;
        EXPECT_TRUE(floor_bits_equal(a.normal, b.normal)) << eye << " " << bx << "," << by;
        EXPECT_TRUE(floor_bits_equal(a.albedo, b.albedo)) << eye << " " << bx << "," << by;
        EXPECT_EQ(plain_way.rays, floor_way.rays) << eye << " " << bx << "," << by;
        EXPECT_EQ(plain_way.evaluations(), floor_way.evaluations()) << eye;
        EXPECT_EQ(plain_way.entered_box, floor_way.entered_box) << eye;
        if (floor.lean()) {
          RayWork unlisted_way;
          PlainFloor::UnlistedRays towards;
          EXPECT_TRUE(floor.unlisted_rays(rt.tracers.tracer(1)->box(), towards));
          const int k = floor.unlisted_colour(rays[i], points[i], towards, unlisted_way, nullptr);
          if (k >= 0) {
            ++n.unlisted;
            const Shaded c = floor.lean_shaded(k);
            EXPECT_TRUE(floor_bits_equal(b.color, c.color)) << eye << " " << bx << "," << by;
            EXPECT_TRUE(floor_bits_equal(b.normal, c.normal)) << eye << " " << bx << "," << by;
            EXPECT_TRUE(floor_bits_equal(b.albedo, c.albedo)) << eye << " " << bx << "," << by;
            EXPECT_EQ(floor_way.rays, unlisted_way.rays) << eye << " " << bx << "," << by;
            EXPECT_EQ(floor_way.evaluations(), unlisted_way.evaluations()) << eye;
            EXPECT_EQ(floor_way.entered_box, unlisted_way.entered_box) << eye;
          } else {
            ++n.declined;
            EXPECT_EQ(unlisted_way.rays, 0) << eye << " " << bx << "," << by;
          }
        }
        const BlobBeam* first = view.of(1);  // the directional light from above
        (first && first[1].clear ? n.clear : n.listed)++;
        n.lit += a.color.x > 0.25;
        n.below += a.normal.z < 0;
      }
    }
  return n;
}

TEST(PlainFloor, ShadesTheFloorAsShadePlainHitDoes) {
  for (const auto& [finish, point] : {std::pair{kFloorShiny, true},
                                      {kFloorMatte, true},
                                      {kFloorShiny, false},
                                      {kFloorMatte, false}}) {
    const FloorCounts above = check_floor("[16, -30, 14]", finish, point);
    EXPECT_GT(above.clear, 200);   // beside the cloud: the plane's test inline
    EXPECT_GT(above.listed, 100);  // near and under it: occluded()
    EXPECT_GT(above.lit, 200);
    EXPECT_EQ(above.below, 0);
    const FloorCounts below =
        check_floor("[16, -30, -14]", finish, point);  // under the floor: its normal turned
    EXPECT_GT(below.below, 1000);
    if (!point && finish == kFloorMatte) {  // lean: most points need no list, some do
      EXPECT_GT(above.unlisted, 1500);
      EXPECT_GT(above.declined, 100);
      EXPECT_GT(below.unlisted, 1000);
    }
  }
}

// The lean floor's frame at one sample (its floor pixels written as they are traced where they
// need no list) against the same frame with anti-aliasing that refines no pixel (every pixel then
// takes records and is shaded with its block's lists): the colour, Z, normal and albedo the same
// bits. Not the steps: the records' lists there are built from the written pixels' points too.
TEST(PlainFloor, FramesFloorPixelsAsTheirRecordsWould) {
  for (const char* eye : {"[16, -30, 14]", "[16, -30, -14]"}) {
    Scene scene = parse_scene(floor_scene_json(eye, kFloorMatte, false), "<test>");
    const TracedScene rt(scene, LipschitzMode::Local);
    constexpr int kW = 96, kH = 72;
    const AovSelection all{true, true, false, true};
    RenderOptions opt;
    opt.spp = 1;
    Film direct(kW, kH, all);
    ASSERT_TRUE(render_frame(scene, rt, opt, direct, nullptr, nullptr));
    scene.image.antialias.threshold = 1e9;  // on, and no pixel differs by that much
    Film records(kW, kH, all);
    FrameStats stats;
    ASSERT_TRUE(render_frame(scene, rt, opt, records, nullptr, &stats));
    EXPECT_EQ(stats.refined_pixels, 0);
    const auto same = [](const auto& a, const auto& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
    };
    EXPECT_FALSE(direct.rgba.empty());
    EXPECT_TRUE(same(direct.rgba, records.rgba)) << eye;
    EXPECT_TRUE(same(direct.depth, records.depth)) << eye;
    EXPECT_TRUE(same(direct.normal, records.normal)) << eye;
    EXPECT_TRUE(same(direct.albedo, records.albedo)) << eye;
  }
}

// The shadow rays' tests that unlisted_colour takes once for the frame (PlainFloor::UnlistedRays)
// answer as clip_to_box does at every origin: lights whose directions have components of either
// sign and of none (the slab's two ends swapped, or a slab the ray runs along), from origins on a
// grid through the cloud's box, on its faces and beside them.
TEST(PlainFloor, UnlistedRaysEnterTheBoxAsClipToBoxFinds) {
  std::string json = floor_scene_json("[16, -30, 14]", kFloorMatte, false);
  const std::string lights =
      R"({ "type": "directional", "direction": [0.5, 0.3, -1], "intensity": 0.7 },
    { "type": "directional", "direction": [-0.2, 0.4, 1], "intensity": 0.3 },
    { "type": "directional", "direction": [0.1, -0.6, -1], "intensity": 0.2, "shadows": false })";
  const size_t at = json.find(lights);
  ASSERT_NE(at, std::string::npos);
  json.replace(at, lights.size(),
               R"({ "type": "directional", "direction": [0.5, -0.3, -1], "intensity": 0.3 },
    { "type": "directional", "direction": [0, 0.4, 1], "intensity": 0.3 },
    { "type": "directional", "direction": [-0.7, 0, -1], "intensity": 0.2 })");
  const Scene scene = parse_scene(json, "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  const PlainFloor floor(scene, rt.embree);
  ASSERT_TRUE(floor.lean());
  const Box& box = rt.tracers.tracer(1)->box();
  PlainFloor::UnlistedRays rays;
  ASSERT_TRUE(floor.unlisted_rays(box, rays));
  ASSERT_EQ(rays.count, 3u);
  int enters = 0, misses = 0;
  for (size_t j = 0; j < rays.count; ++j) {
    const PlainFloor::UnlistedRays::Light& l = rays.light[j];
    EXPECT_TRUE(floor_bits_equal(l.to_light, -scene.lights[j + 1].direction)) << j;
    for (int ix = -2; ix <= 6; ++ix)
      for (int iy = -2; iy <= 6; ++iy)
        for (int iz = -2; iz <= 6; ++iz) {
          // Quarters of the box's extent from a quarter before lo to a half past hi: the faces
          // themselves among them.
          const Vec3 o{box.lo.x + (box.hi.x - box.lo.x) * ix / 4,
                       box.lo.y + (box.hi.y - box.lo.y) * iy / 4,
                       box.lo.z + (box.hi.z - box.lo.z) * iz / 4};
          double t0 = 0, t1 = std::numeric_limits<double>::infinity();
          const bool clipped = clip_to_box({o, l.to_light}, box, t0, t1);
          EXPECT_EQ(l.enters(o), clipped) << j << " " << ix << "," << iy << "," << iz;
          (clipped ? enters : misses)++;
        }
  }
  EXPECT_GT(enters, 500);
  EXPECT_GT(misses, 500);
}

TEST(PlainFloor, NoneWithoutAPlainFloor) {
  // A mirror floor takes shade()'s long way; a floor beside two primitives, Embree's.
  const Scene mirror = parse_scene(
      floor_scene_json("[16, -30, 14]", R"({ "color": [1, 1, 1], "reflection": 0.5 })"), "<test>");
  const TracedScene rt(mirror, LipschitzMode::Local);
  EXPECT_EQ(PlainFloor(mirror, rt.embree).object(), -1);
  const Scene plain = parse_scene(R"({
    "objects": [
      { "shape": { "type": "plane", "normal": [0, 0, 1], "distance": -2 } },
      { "shape": { "type": "sphere", "center": [0, 0, 0], "radius": 1 } } ] })",
                                  "<test>");
  const TracedScene rt2(plain, LipschitzMode::Local);
  EXPECT_EQ(PlainFloor(plain, rt2.embree).object(), -1);
}

}  // namespace
}  // namespace softtrace

// The frame shades a camera hit on a plain object (shades_plain: an opaque material of its own,
// no mirror, no transparency) by shade_plain_hit, inline in its loop, and every other hit by
// shade(): the two must give the same colour, normal and albedo to the bit, and count the same
// shadow rays' work. The objects here are a blob sum, a floor and a sphere, matte, with a phong
// and a specular highlight, brilliance and metallic, under an ambient, a directional and a point
// light; a mirror beside them is no plain object.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "film/film.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/shading.h"
#include "render/shadow_beams.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

const char* const kScene = R"({
  "camera": { "eye": [30, -44, 22], "target": [0, 0, 4], "fov": 40 },
  "lights": [
    { "type": "ambient", "intensity": 0.2 },
    { "type": "directional", "direction": [-0.6, 1, -1.6], "intensity": 0.8 },
    { "type": "point", "position": [-6, -5, 12], "intensity": 0.6 }
  ],
  "objects": [
    { "material": { "color": [0.62, 0.6, 0.55], "specular": 0.3, "roughness": 0.05 },
      "shape": { "type": "plane", "normal": [0, 0, 1], "distance": 0 } },
    { "material": { "color": [0.85, 0.45, 0.35], "phong": 0.6, "phong_size": 20,
                    "brilliance": 1.5 },
      "field": { "type": "soft_blend", "children": [
        { "type": "soft_object", "translate": [0, 0, 5],
          "distance": { "type": "lp_metric", "radii": [9, 9, 9], "n": 2 } },
        { "type": "soft_object", "translate": [5, 3, 9],
          "distance": { "type": "lp_metric", "radii": [6, 6, 6], "n": 2 } } ] } },
    { "material": { "color": [0.35, 0.55, 0.85], "phong": 0.8, "metallic": 0.7 },
      "shape": { "type": "sphere", "center": [12, -6, 3], "radius": 3 } },
    { "material": { "color": [0.7, 0.7, 0.7] },
      "shape": { "type": "sphere", "center": [-12, -4, 4], "radius": 3 } },
    { "material": { "color": [0.9, 0.9, 0.9], "reflection": 0.5 },
      "shape": { "type": "sphere", "center": [-4, -14, 3], "radius": 3 } }
  ]
})";

bool same_bits(const Vec3& a, const Vec3& b) {
  return std::memcmp(&a, &b, sizeof(Vec3)) == 0;
}

TEST(ShadePlain, EveryPlainHitIsShadedAsShadeDoes) {
  const Scene scene = parse_scene(kScene, "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  ASSERT_EQ(scene.objects.size(), 5u);
  for (size_t o = 0; o < 4; ++o) EXPECT_TRUE(shades_plain(scene, scene.objects[o])) << o;
  EXPECT_FALSE(shades_plain(scene, scene.objects[4]));  // the mirror takes shade()'s long way

  const int width = 96, height = 72;
  const ViewCamera camera(scene.camera, width, height);
  // The scene's shadow lists, of a block of the one point shaded: a sum of two blobs takes none
  // (ShadowBeams::kFewBlobs), so both shadings trace each shadow ray alone, the same rays.
  const ShadowBeams beams(scene, rt.tracers);
  ShadowBeams::Lists block_lists;
  int starts[17] = {0};
  std::fill(starts + 1, starts + 17, 1);
  int plain_hits[4] = {0, 0, 0, 0}, lit = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit hit = rt.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
      if (!hit.hit || hit.face > 0) continue;
      const SceneObject& obj = scene.objects[size_t(hit.object)];
      if (!shades_plain(scene, obj)) continue;
      const Vec3 p = ray.o + ray.d * hit.t;
      const ShadowBeams::Point point{p, ray_offset(obj, p, ray.cone_at(hit.t))};
      ShadowListsOnDemand lists(beams, &point, starts, block_lists);
      lists.block(0);
      lists.at(point);
      RayWork long_way, short_way;
      const Shaded a =
          shade(scene, rt.tracers, rt.embree, ray, hit, long_way, nullptr, 1, 1, nullptr, &lists);
      const Shaded b = shade_plain_hit(scene, rt.tracers, rt.embree, ray, hit, obj.material,
                                       short_way, nullptr, lists);
      ASSERT_TRUE(same_bits(a.color, b.color)) << x << "," << y;
      ASSERT_TRUE(same_bits(a.normal, b.normal)) << x << "," << y;
      ASSERT_TRUE(same_bits(a.albedo, b.albedo)) << x << "," << y;
      ASSERT_EQ(long_way.rays, short_way.rays) << x << "," << y;
      ASSERT_EQ(long_way.evaluations(), short_way.evaluations()) << x << "," << y;
      // Without lists (a frame of few blobs): shade_plain_at from the same point and offset.
      RayWork alone, alone_short;
      const Shaded c = shade(scene, rt.tracers, rt.embree, ray, hit, alone);
      const Shaded d = shade_plain_at(scene, rt.tracers, rt.embree, ray, hit, obj.material, p,
                                      point.margin, alone_short, nullptr, nullptr);
      ASSERT_TRUE(same_bits(c.color, d.color)) << x << "," << y;
      ASSERT_TRUE(same_bits(c.normal, d.normal)) << x << "," << y;
      ASSERT_TRUE(same_bits(c.albedo, d.albedo)) << x << "," << y;
      ASSERT_EQ(alone.rays, alone_short.rays) << x << "," << y;
      ASSERT_EQ(alone.evaluations(), alone_short.evaluations()) << x << "," << y;
      ++plain_hits[hit.object];
      lit += a.color.x > 0;
    }
  // Every plain object seen, and lit.
  for (int o = 0; o < 4; ++o) EXPECT_GT(plain_hits[o], 20) << o;
  EXPECT_GT(lit, 1000);
}

// A sum of a few blobs takes no shadow lists (ShadowBeams::kFewBlobs; pov:molecule's three
// balls): the frame shades such a scene's plain hits inline too (shade_plain_at), from the point
// and offset it makes for them, not shade()'s. Its pixels' colour, normal and albedo must be
// shade()'s of the pixel-centre ray to the bit. The blobs (a phong highlight and brilliance) set
// the frame on that way; a sphere with a specular highlight is compared, whose hit is exact (the
// blobs' hits are the certified beams' march, which may place them elsewhere within the
// tolerance than a ray traced alone), under an ambient, a directional and two point lights, one
// without shadows, and a mirror beside them takes shade()'s long way in both.
const char* const kFewBlobs = R"({
  "camera": { "eye": [0.6, -9, 3.2], "target": [0, 0, 0], "fov": 40 },
  "lights": [
    { "type": "ambient", "intensity": 0.15 },
    { "type": "point", "position": [-10, -14, 12] },
    { "type": "point", "position": [12, -10, 6], "color": [0.35, 0.35, 0.35], "shadows": false },
    { "type": "directional", "direction": [0.3, 0.5, -1], "intensity": 0.4 }
  ],
  "objects": [
    { "material": { "color": [0.85, 0.12, 0.1], "phong": 0.6, "phong_size": 60,
                    "brilliance": 1.3 },
      "iso": 0.65,
      "field": { "type": "soft_blend", "children": [
        { "type": "soft_object", "strength": 2,
          "distance": { "type": "lp_metric", "radii": [1.6, 1.6, 1.6], "n": 2 } },
        { "type": "soft_object", "translate": [1.06, 0.26, -0.8],
          "distance": { "type": "lp_metric", "radii": [1, 1, 1], "n": 2 } },
        { "type": "soft_object", "translate": [-0.88, -0.64, -0.8],
          "distance": { "type": "lp_metric", "radii": [1, 1, 1], "n": 2 } } ] } },
    { "material": { "color": [0.35, 0.55, 0.85], "specular": 0.4, "roughness": 0.03 },
      "shape": { "type": "sphere", "center": [2.4, 1, 0.6], "radius": 0.8 } },
    { "material": { "color": [0.9, 0.9, 0.9], "reflection": 0.5 },
      "shape": { "type": "sphere", "center": [-2.4, 1.5, 0.4], "radius": 0.9 } }
  ]
})";

TEST(ShadePlain, AFrameWithoutShadowListsShadesAsShadeDoes) {
  const Scene scene = parse_scene(kFewBlobs, "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  ASSERT_TRUE(shades_plain(scene, scene.objects[0]));
  ASSERT_TRUE(shades_plain(scene, scene.objects[1]));
  ASSERT_FALSE(shades_plain(scene, scene.objects[2]));
  constexpr int kW = 96, kH = 72;
  RenderOptions opt;
  opt.spp = 1;
  Film film(kW, kH, AovSelection{true, true, false, true});
  ASSERT_TRUE(render_frame(scene, rt, opt, film, nullptr, nullptr));
  const ViewCamera camera(scene.camera, kW, kH);
  const auto same = [](float a, double b) {
    const float f = static_cast<float>(b);
    return std::memcmp(&a, &f, sizeof f) == 0;
  };
  int hits[3] = {0, 0, 0}, differ = 0, highlit = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit hit = rt.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
      if (!hit.hit) continue;
      ++hits[hit.object];
      if (hit.object == 0) continue;
      const size_t i = size_t(y * kW + x);
      ASSERT_TRUE(same(film.depth[i], hit.t)) << x << "," << y;
      RayWork work;
      const Shaded sh = shade(scene, rt.tracers, rt.embree, ray, hit, work);
      Vec3 sum{0, 0, 0};  // the frame's sum of one sample, from 0
      sum += sh.color;
      bool equal = true;
      for (int k = 0; k < 3; ++k)
        equal = equal && same(film.rgba[i * 4 + k], sum[k]) &&
                same(film.normal[i * 3 + k], sh.normal[k]) &&
                same(film.albedo[i * 3 + k], sh.albedo[k]);
      differ += !equal;
      highlit += hit.object == 1 && sh.color.x > 0.6;
    }
  EXPECT_EQ(differ, 0);
  for (int o = 0; o < 3; ++o) EXPECT_GT(hits[o], 100) << o;
  EXPECT_GT(highlit, 5);  // the specular highlight is in the picture
}

}  // namespace
}  // namespace softtrace

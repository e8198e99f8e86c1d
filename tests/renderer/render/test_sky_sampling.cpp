// The gradient sky, ambient occlusion and adaptive anti-aliasing (docs/scene-format.md
// "background", "ambient_occlusion", "antialias"; docs/math.md §12.4-12.5): what each changes in
// a picture, and that the picture is still the same bits for any thread count and tile split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/antialias.h"
#include "render/frame.h"
#include "render/progress.h"
#include "render/shading.h"

namespace softtrace {
namespace {

const char* kScene = "scenes/sky_clay_blob.json";

TEST(Sky, GradientRunsFromBottomStraightDownToTopStraightUp) {
  SkyGradient sky;
  sky.bottom = {0.2, 0.4, 0.6};
  sky.top = {1, 0.5, 0};
  EXPECT_EQ(sky.seen({0, 0, -3}).x, 0.2);
  EXPECT_EQ(sky.seen({0, 0, 2}).x, 1);
  EXPECT_DOUBLE_EQ(sky.seen({1, 1, 0}).y, 0.45);  // the horizon: the mean
  sky.up = {1, 0, 0};
  EXPECT_EQ(sky.seen({5, 0, 0}).z, 0);
}

Scene small(const std::string& text) {
  Scene s = parse_scene(text, "sky.json");
  s.image.width = 32;
  s.image.height = 24;
  return s;
}

// A ball in the middle of the view under a sky that is dark straight down and bright straight
// up: every pixel is opaque, and the sky brightens up the image's edge columns.
TEST(Sky, IsOpaqueAndBrightensUpwards) {
  const Scene scene = small(R"({
    "camera": {"eye": [0, -20, 0], "target": [0, 0, 0], "fov": 60},
    "background": {"gradient": [[0, 0, 0], [1, 1, 1]]},
    "objects": [{"field": {"type": "soft_object",
                 "distance": {"type": "lp_metric", "radii": [3, 3, 3], "n": 2}}}]})");
  const TracedScene rt(scene, LipschitzMode::Local);
  Film film(32, 24);
  ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, film, nullptr, nullptr));
  int checked = 0;
  for (int y = 0; y < 24; ++y) {
    EXPECT_EQ(film.rgba[(y * 32) * 4 + 3], 1.0f);
    if (y > 0) {
      EXPECT_LT(film.rgba[(y * 32) * 4], film.rgba[((y - 1) * 32) * 4]) << y;  // row 0 is the top
      EXPECT_EQ(film.depth[y * 32], INFINITY);                                 // a miss
      ++checked;
    }
  }
  EXPECT_EQ(checked, 23);
  EXPECT_NEAR(film.rgba[(12 * 32) * 4], 0.5, 0.05);  // the horizon, mid-height
}

// A ball of radius 3 resting on a floor, lit by ambient light only: with ambient occlusion, the
// floor beside the ball (a crease) is darker than the floor a little farther out, which is darker
// than the floor in the open, which keeps all of its light.
TEST(AmbientOcclusion, ACreaseIsDarkerThanAnOpenFace) {
  const char* text = R"({
    "camera": {"eye": [0, -20, 10], "target": [0, 0, 0]},
    "image": {"ambient_occlusion": {"samples": 32, "distance": 6}},
    "lights": [{"type": "ambient", "intensity": 1}],
    "objects": [
      {"name": "floor", "material": {"color": [1, 1, 1]},
       "shape": {"type": "plane", "normal": [0, 0, 1], "distance": 0}},
      {"name": "ball", "material": {"color": [1, 1, 1]}, "field": {"type": "soft_object",
       "translate": [0, 0, 3], "distance": {"type": "lp_metric", "radii": [6, 6, 6], "n": 2}}}]})";
  // The colour straight down onto the floor at (x, 0) (beyond the ball's radius).
  const auto floor_at = [](const Scene& scene, double x) {
    const TracedScene rt(scene, LipschitzMode::Local);
    const Ray ray{{x, 0, 30}, {0, 0, -1}, 0, 1e-4};
    const TraceHit hit = rt.embree.intersect(ray, 0, INFINITY);
    EXPECT_TRUE(hit.hit);
    EXPECT_NEAR(hit.t, 30, 1e-6) << x;  // the floor, not the ball
    RayWork work;
    const Shaded s = shade(scene, rt.tracers, rt.embree, ray, hit, work);
    EXPECT_EQ(work.rays, scene.image.occlusion.samples);  // once for all ambient lights
    return s.color.x;
  };
  const Scene scene = parse_scene(text, "ao.json");
  const double crease = floor_at(scene, 3.2), near = floor_at(scene, 4.5),
               open = floor_at(scene, 20);
  EXPECT_EQ(open, 1);  // nothing within 6 of it: all of the ambient light
  EXPECT_LT(crease, 0.9);
  EXPECT_LT(crease, near);
  EXPECT_LT(near, open);

  Scene plain = parse_scene(text, "ao.json");
  plain.image.occlusion = AmbientOcclusion{};
  EXPECT_EQ(floor_at(plain, 3.2), 1);  // without occlusion the crease has all of it too
}

// The same scene with and without adaptive anti-aliasing: the first pass is the plain render, so
// a pixel whose four neighbours all agree with it within the threshold (a flat region) keeps
// exactly its bits; the pixels traced again are the edges', and some of them change.
TEST(AdaptiveAntialias, OnlyPixelsThatDifferFromANeighbourAreRefined) {
  Scene scene = load_scene(test::source_path(kScene));
  scene.image.width = 64;
  scene.image.height = 48;
  scene.image.occlusion = AmbientOcclusion{};  // faster; the edges are the geometry's
  const TracedScene rt(scene, LipschitzMode::Local);
  const AovSelection aovs{true, true, true, true};
  Film adaptive(64, 48, aovs), plain(64, 48, aovs);
  FrameStats stats;
  Progress progress("rendering", 64 * 48, false);
  ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, adaptive, &progress, &stats));
  const double threshold = scene.image.antialias.threshold;
  scene.image.antialias = Antialias{};
  ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, plain, nullptr, nullptr));

  const auto differ = [&](int x0, int y0, int x1, int y1) {
    if (x1 < 0 || y1 < 0 || x1 >= 64 || y1 >= 48) return false;
    // POV-Ray's distance of the colours gamma-encoded by 2.5 (R, G, B; A as it is).
    const auto encoded = [&](int x, int y, int k) {
      const float c = plain.rgba[(y * 64 + x) * 4 + k];
      return k < 3 ? std::pow(std::max(c, 0.0f), 1 / 2.5f) : c;
    };
    double d = 0;
    for (int k = 0; k < 4; ++k) d += std::fabs(double(encoded(x0, y0, k)) - encoded(x1, y1, k));
    return d > threshold;
  };
  long long flat = 0, edges = 0, changed = 0, mixed_normals = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool edge = differ(x, y, x - 1, y) || differ(x, y, x + 1, y) ||
                        differ(x, y, x, y - 1) || differ(x, y, x, y + 1);
      const size_t i = size_t(y * 64 + x) * 4;
      bool same = true;
      for (int k = 0; k < 4; ++k) same = same && adaptive.rgba[i + k] == plain.rgba[i + k];
      edges += edge;
      flat += !edge;
      changed += !same;
      if (!edge) {
        EXPECT_TRUE(same) << "a flat pixel was refined: " << x << "," << y;
      }
      // Albedo and normal: a flat pixel keeps its centre ray's; a refined one takes the mean of
      // its refined samples', which across an edge is a mix (a normal shorter than 1).
      const size_t j = size_t(y * 64 + x) * 3;
      double length2 = 0;
      for (int k = 0; k < 3; ++k) {
        if (!edge) {
          EXPECT_EQ(adaptive.normal[j + k], plain.normal[j + k]);
          EXPECT_EQ(adaptive.albedo[j + k], plain.albedo[j + k]);
        }
        length2 += double(adaptive.normal[j + k]) * adaptive.normal[j + k];
        EXPECT_GE(adaptive.albedo[j + k], 0.0f);
        EXPECT_LE(adaptive.albedo[j + k], 1.0f);
      }
      EXPECT_LE(length2, 1 + 1e-5);
      mixed_normals += edge && length2 > 0 && length2 < 0.98;
    }
  EXPECT_EQ(stats.refined_pixels, edges);
  EXPECT_GT(edges, 20);
  EXPECT_GT(flat, 64 * 48 / 2);
  EXPECT_GT(changed, edges / 2);
  EXPECT_GT(mixed_normals, edges / 10);
  EXPECT_EQ(stats.primary_rays, 64 * 48 + edges * 9);  // depth 3: 9 samples each
  // The progress bar counts both passes: the second's pixels, known after the first, as 9 each.
  EXPECT_EQ(progress.total(), 64 * 48 + edges * 9);
  EXPECT_EQ(progress.done(), progress.total());
}

// The colours are compared gamma-encoded by the scene's Antialias_Gamma ("gamma"): two dark
// pixels, 0.001 and 0.01 linear, differ by 0.095 at POV-Ray's 2.5 (0.01^0.4 - 0.001^0.4) and by
// 0.009 at gamma 1, so a threshold of 0.05 refines them at 2.5 and not at 1; a bright pair
// (0.5, 0.56) differs by 0.06 at gamma 1 and by 0.035 at 2.5: the other way round.
TEST(AdaptiveAntialias, GammaEncodesTheColoursCompared) {
  const auto refined = [](double gamma, float a, float b) {
    Antialias aa;
    aa.threshold = 0.05;
    aa.gamma = gamma;
    AdaptivePixels pixels(aa, PixelRect{0, 0, 2, 1}, 2, 1);
    const float left[4] = {a, a, 0, 1}, right[4] = {b, a, 0, 1};
    pixels.set_first(0, 0, left);
    pixels.set_first(1, 0, right);
    pixels.decide();
    return pixels.refined();
  };
  EXPECT_EQ(refined(2.5, 0.001f, 0.01f), 2);
  EXPECT_EQ(refined(1, 0.001f, 0.01f), 0);
  EXPECT_EQ(refined(2.5, 0.5f, 0.56f), 0);
  EXPECT_EQ(refined(1, 0.5f, 0.56f), 2);
  EXPECT_EQ(Antialias{}.gamma, 2.5);  // POV-Ray's default
}

// The showcase scene (sky, occlusion, adaptive anti-aliasing): 1 and 2 threads, and three tiles
// merged, give the same bits; --antialias overrides the scene's threshold.
TEST(AdaptiveAntialias, SameBitsForThreadsAndTileSplits) {
  const std::string dir = test::temp_dir("sky_sampling");
  const std::string base = "render " + test::source_path(kScene) +
                           " -q --width 64 --height 48 --aov depth,normal,albedo ";
  ASSERT_EQ(test::run_softtrace(base + "--threads 1 -o " + dir + "/one.exr").status, 0);
  ASSERT_EQ(test::run_softtrace(base + "--threads 2 -o " + dir + "/two.exr").status, 0);
  ASSERT_EQ(test::render_tiles_and_merge(base, dir, 3), dir + "/merged.exr");
  const ImageFile one = read_image(dir + "/one.exr"), two = read_image(dir + "/two.exr"),
                  merged = read_image(dir + "/merged.exr");
  EXPECT_EQ(one.pixels, two.pixels);
  ASSERT_EQ(one.channels, merged.channels);
  EXPECT_EQ(one.pixels, merged.pixels);

  ASSERT_EQ(test::run_softtrace(base + "--antialias 100 -o " + dir + "/never.exr").status, 0);
  const ImageFile never = read_image(dir + "/never.exr");
  EXPECT_NE(one.pixels, never.pixels);  // nothing differs by 100: no pixel refined
  const test::RunResult bad = test::run_softtrace(base + "--antialias -1 -o " + dir + "/bad.exr");
  EXPECT_EQ(bad.status, 2);
}

}  // namespace
}  // namespace softtrace

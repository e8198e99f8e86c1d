// POV-Ray's finish and light terms (docs/math.md §12) on their own, and what they add to a render:
// the albedo AOV and deterministic area-light jitter across tile splits. The comparison with
// POV-Ray itself is tools/pov_finish.py (CTest pov_finish).
#include <gtest/gtest.h>

#include <cmath>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/finish.h"
#include "render/lights.h"

namespace softtrace {
namespace {

const Vec3 kWhite{1, 1, 1};

TEST(Finish, DefaultsAreLambert) {
  const Material m;
  const Vec3 d = diffuse_light(m, 0.3, Vec3{0.5, 1, 2});
  EXPECT_EQ(d.x, 0.5 * 0.3);
  EXPECT_EQ(d.z, 2 * 0.3);
  const Vec3 h =
      highlights(m, {0, 0, 1}, normalize(Vec3{0, 1, -1}), normalize(Vec3{0, -1, 1}), kWhite);
  EXPECT_EQ(h.x, 0);
}

TEST(Finish, BrillianceRaisesTheCosine) {
  Material m;
  m.brilliance = 3;
  m.diffuse = 0.6;
  EXPECT_DOUBLE_EQ(diffuse_light(m, 0.5, kWhite).y, 0.6 * 0.125);
}

TEST(Finish, PhongAndSpecularPeakAtTheMirrorDirection) {
  Material m;
  m.phong = 0.7;
  m.specular = 0.4;
  const Vec3 n{0, 0, 1}, d = normalize(Vec3{1, 0, -1}), to_light = normalize(Vec3{1, 0, 1});
  // The mirror of the view is the light's direction: both cosines are 1.
  EXPECT_NEAR(highlights(m, n, d, to_light, kWhite).x, 0.7 + 0.4, 1e-12);
  // 30 degrees off: phong cos^40 of the mirror angle, specular cos^(1/0.05) of the half angle.
  const double a = 30 * M_PI / 180;
  const Vec3 off = normalize(Vec3{std::sin(M_PI / 4 + a), 0, std::cos(M_PI / 4 + a)});
  const Vec3 half = normalize(off - d);
  const double expect = 0.7 * std::pow(std::cos(a), 40) + 0.4 * std::pow(dot(half, n), 20);
  EXPECT_NEAR(highlights(m, n, d, off, kWhite).x, expect, 1e-12);
}

TEST(Finish, PhongSizeFromSixtyDropsTheFaintestTail) {
  Material m;
  m.phong = 1;
  m.phong_size = 60;
  const Vec3 n{0, 0, 1}, d{0, 0, -1};                  // the mirror direction is +z
  const Vec3 grazing = normalize(Vec3{1, 0, 0.0005});  // cos 0.0005 <= 0.0008
  EXPECT_EQ(highlights(m, n, d, grazing, kWhite).x, 0);
  m.phong_size = 59;
  EXPECT_GT(highlights(m, n, d, grazing, kWhite).x, 0);
}

TEST(Finish, MetallicHighlightsTakeTheSurfaceColourHeadOn) {
  Material m;
  m.phong = 1;
  m.metallic = 1;
  m.color = {0.9, 0.6, 0.2};
  const Vec3 n{0, 0, 1}, d{0, 0, -1};
  // Head-on POV's Fresnel curve is 0.014567225 / 1.12^2 - 0.011612903 = 3.8e-9: the pigment.
  const Vec3 h = highlights(m, n, d, n, kWhite);
  EXPECT_NEAR(h.x, 0.9, 1e-8);
  EXPECT_NEAR(h.z, 0.2, 1e-8);
}

TEST(Lights, SpotConeFalloffAndFading) {
  Light l;
  l.type = Light::Type::Spot;
  l.position = {0, 0, 10};
  l.direction = {0, 0, -1};
  l.cos_radius = std::cos(10 * M_PI / 180);
  l.cos_falloff = std::cos(20 * M_PI / 180);
  const auto at_angle = [&](double deg, LightArrival& out) {
    const Vec3 p{10 * std::tan(deg * M_PI / 180), 0, 0};
    return light_arrival(l, p, p, out);
  };
  LightArrival a;
  ASSERT_TRUE(at_angle(5, a));
  EXPECT_EQ(a.light.x, 1);        // inside the radius: full light (tightness 0)
  EXPECT_FALSE(at_angle(25, a));  // beyond the falloff
  ASSERT_TRUE(at_angle(15, a));   // between: the cubic with flat ends
  const double u = (std::cos(15 * M_PI / 180) - l.cos_falloff) / (l.cos_radius - l.cos_falloff);
  EXPECT_NEAR(a.light.x, (3 - 2 * u) * u * u, 1e-12);

  Light f;
  f.type = Light::Type::Point;
  f.position = {0, 0, 4};
  f.fade_distance = 4;
  f.fade_power = 2;
  ASSERT_TRUE(light_arrival(f, {0, 0, 0}, {0, 0, 0}, a));
  EXPECT_DOUBLE_EQ(a.light.x, 1);  // exactly the colour at fade_distance
  ASSERT_TRUE(light_arrival(f, {0, 0, -4}, {0, 0, -4}, a));
  EXPECT_DOUBLE_EQ(a.light.x, 2.0 / (1 + 4));  // twice as far: 2 / (1 + 2^2)
}

// scenes/finish_atoms.json has a jittered, adaptive area light: its parts merge to the whole
// frame's bits, and the albedo AOV is the mean of the 2 samples' materials' colours (0 for a
// sample that meets nothing): a material's colour, or an edge's mix of two.
TEST(FinishRender, JitteredAreaLightMergesAcrossTilesAndAlbedoIsTheMaterial) {
  const std::string dir = test::temp_dir("finish_render");
  const std::string base = "render " + test::source_path("scenes/finish_atoms.json") +
                           " -q --width 48 --height 36 --spp 2 --aov albedo,steps ";
  ASSERT_EQ(test::run_softtrace(base + "-o " + dir + "/full.exr").status, 0);
  ASSERT_EQ(test::render_tiles_and_merge(base, dir, 3), dir + "/merged.exr");
  const ImageFile full = read_image(dir + "/full.exr"), merged = read_image(dir + "/merged.exr");
  ASSERT_EQ(full.channels, merged.channels);
  EXPECT_EQ(full.pixels, merged.pixels);

  const int r = full.channel("albedo.R"), g = full.channel("albedo.G"), a = full.channel("A");
  ASSERT_GE(r, 0);
  const double colours[3][2] = {{0.75, 0.1}, {0.8, 0.78}, {0, 0}};  // atoms, slab, nothing
  const auto mean = [&](int c0, int c1, int k) {
    return static_cast<float>((colours[c0][k] + colours[c1][k]) / 2);
  };
  int atoms = 0, slab = 0, background = 0, mixed = 0;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) {
      const float red = full.at(x, y, r), green = full.at(x, y, g);
      bool found = false;
      for (int c0 = 0; c0 < 3 && !found; ++c0)
        for (int c1 = c0; c1 < 3 && !found; ++c1) {
          if (red != mean(c0, c1, 0) || green != mean(c0, c1, 1)) continue;
          found = true;
          atoms += c0 == 0 && c1 == 0;
          slab += c0 == 1 && c1 == 1;
          background += c0 == 2 && full.at(x, y, a) == 0;
          mixed += c0 != c1;
        }
      if (!found) ADD_FAILURE() << "albedo (" << red << ", " << green << ") at " << x << "," << y;
    }
  EXPECT_GT(atoms, 100);
  EXPECT_GT(slab, 100);
  EXPECT_GT(background, 10);
  EXPECT_GT(mixed, 10);  // the silhouettes' pixels
}

}  // namespace
}  // namespace softtrace

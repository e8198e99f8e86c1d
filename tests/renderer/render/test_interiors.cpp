// Nested and overlapping transparent objects (docs/math.md §12.6, "Interiors"): POV-Ray 3.7's
// interior list, which gives the index ratio at each surface from the medium the ray is in and the
// one it passes into; the tracer finding where a ray inside two field solids leaves each; and
// pictures in which the list decides what is seen. The comparison with POV-Ray is
// tools/pov_finish.py (glass_in_glass, overlapping_glass, glass_in_csg).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/frame.h"
#include "render/transparency.h"
#include "scene/scene.h"

namespace softtrace {
// Named, not anonymous: the unity build joins this file with others that have their own kInf.
namespace interiors_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Interiors, CrossingFollowsPovRaysInteriorList) {
  const int A = 3, B = 7;  // objects; A's ior 1.5, B's 1.2
  Crossing c;
  ASSERT_TRUE(cross(Interiors{}, A, 1.5, c));  // from the air into A
  EXPECT_DOUBLE_EQ(c.eta, 1 / 1.5);
  ASSERT_EQ(c.next.size(), 1);
  const Interiors in_a = c.next;
  ASSERT_TRUE(cross(in_a, B, 1.2, c));  // from A into B: (A (B ...
  EXPECT_DOUBLE_EQ(c.eta, 1.5 / 1.2);
  ASSERT_EQ(c.next.size(), 2);
  EXPECT_EQ(c.next.back().object, B);
  const Interiors in_ab = c.next;
  ASSERT_TRUE(cross(in_ab, B, 1.2, c));  // out of the inner B, back into A: (A (B B) ...
  EXPECT_DOUBLE_EQ(c.eta, 1.2 / 1.5);
  ASSERT_EQ(c.next.size(), 1);
  EXPECT_EQ(c.next.back().object, A);
  // Out of A while in B (overlapping objects, (A (B A) ...): the overlap was B's, so the ray
  // stays in B's medium: ratio 1.
  ASSERT_TRUE(cross(in_ab, A, 1.5, c));
  EXPECT_EQ(c.eta, 1);
  ASSERT_EQ(c.next.size(), 1);
  EXPECT_EQ(c.next.back().object, B);
  ASSERT_TRUE(cross(in_a, A, 1.5, c));  // out of A into the air
  EXPECT_DOUBLE_EQ(c.eta, 1.5);
  EXPECT_TRUE(c.next.empty());
  // A list Interiors::kMax deep enters nothing more, but can still be left.
  Interiors full;
  for (int k = 0; k < Interiors::kMax; ++k) ASSERT_TRUE(full.push(k, 1.1));
  EXPECT_FALSE(cross(full, 100, 1.5, c));
  EXPECT_TRUE(cross(full, Interiors::kMax - 1, 1.1, c));
}

TEST(Interiors, FresnelRatioIsPovRaysComputeRelativeIor) {
  const int A = 3, B = 7;
  Interiors in_a, in_ab;
  in_a.push(A, 1.5);
  in_ab.push(A, 1.5);
  in_ab.push(B, 1.2);
  EXPECT_DOUBLE_EQ(fresnel_ratio(Interiors{}, A, 1.5), 1.5);  // from the air
  EXPECT_DOUBLE_EQ(fresnel_ratio(in_a, A, 1.5), 1 / 1.5);     // out into the air
  EXPECT_DOUBLE_EQ(fresnel_ratio(in_a, B, 1.2), 1.2 / 1.5);   // from A into B
  EXPECT_DOUBLE_EQ(fresnel_ratio(in_ab, A, 1.5), 1.2 / 1.5);  // out of A while in B
  // Out of the innermost B into A: POV-Ray takes the innermost's ior over B's own, 1.
  EXPECT_EQ(fresnel_ratio(in_ab, B, 1.2), 1);
}

// Two concentric soft balls (murakami, iso 0.5: the surface at 0.541 of the radius), objects 0
// (radius 10: surface 5.41) and 1 (radius 5: surface 2.71).
const char* kNestedBalls = R"({
  "camera": {"eye": [0, -30, 0], "target": [0, 0, 0]},
  "lights": [],
  "objects": [
    {"name": "outer", "material": {"transmit": 1, "ior": 1.5},
     "field": {"type": "soft_object", "potential": {"type": "murakami"},
               "distance": {"type": "lp_metric", "radii": [10, 10, 10], "n": 2}}},
    {"name": "inner", "material": {"transmit": 1, "ior": 1.3},
     "field": {"type": "soft_object", "potential": {"type": "murakami"},
               "distance": {"type": "lp_metric", "radii": [5, 5, 5], "n": 2}}}]})";

TEST(Interiors, ARayInsideTwoFieldSolidsLeavesTheInnerThenTheOuter) {
  const Scene scene = parse_scene(kNestedBalls, "nested.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  const double surface = std::sqrt(1 - std::sqrt(0.5));
  const Ray ray{{0, 0, 0.3}, normalize(Vec3{1, 2, 0.5}), 0, 1e-6};
  const double from_centre = 0.3 * 0.5 / std::sqrt(5.25);  // d . o
  const auto exit_at = [&](double radius) {
    return -from_centre + std::sqrt(from_centre * from_centre - 0.09 + radius * radius);
  };
  Interiors both;
  both.push(0, 1.5);
  both.push(1, 1.3);
  const TraceHit inner = rt.embree.intersect(ray, 0, kInf, nullptr, both);
  ASSERT_TRUE(inner.hit);
  EXPECT_EQ(inner.object, 1);
  EXPECT_FALSE(inner.on_box_face);
  EXPECT_NEAR(inner.t, exit_at(5 * surface), 1e-3);
  Interiors outer_only;
  outer_only.push(0, 1.5);
  const Ray on{ray.o + ray.d * (inner.t + 1e-3), ray.d, 0, 1e-6};
  const TraceHit outer = rt.embree.intersect(on, 0, kInf, nullptr, outer_only);
  ASSERT_TRUE(outer.hit);
  EXPECT_EQ(outer.object, 0);
  EXPECT_NEAR(inner.t + 1e-3 + outer.t, exit_at(10 * surface), 1e-3);
  // Told of the inner solid only (one object inside, as the tracer once was), the ray finds the
  // outer solid where it starts.
  EXPECT_LT(rt.embree.intersect(ray, 0, kInf, nullptr, 1).t, 1e-6);
}

// Glass that shows nothing but what it lets through (transmit 1, no ambient, diffuse or
// highlight) in front of a lit floor, rendered at 40x30.
std::vector<float> render_rgb(const std::string& dir, const std::string& name,
                              const std::string& glass_objects) {
  {
    std::ofstream f(dir + "/" + name + ".json");
    f << R"({"camera": {"eye": [2, -16, 7], "target": [0, 0, 0], "fov": 35},
      "image": {"max_trace_level": 12},
      "lights": [{"type": "point", "position": [8, -6, 12], "intensity": 1}],
      "background": [0.2, 0.3, 0.45],
      "objects": [
        {"name": "floor", "material": {"color": [0.8, 0.7, 0.5]},
         "shape": {"type": "plane", "normal": [0.1, 0.2, 1], "distance": -4}},)"
      << glass_objects << "]}";
  }
  const std::string out = dir + "/" + name + ".exr";
  EXPECT_EQ(test::run_softtrace("render " + dir + "/" + name +
                                ".json -q --width 40 --height 30 --flatten -o " + out)
                .status,
            0);
  const ImageFile image = read_image(out);
  std::vector<float> rgb;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      for (const char* c : {"R", "G", "B"}) rgb.push_back(image.at(x, y, image.channel(c)));
  return rgb;
}

const char* kGlass = R"({"transmit": 1, "ambient": 0, "diffuse": 0, "ior": 1.5})";

std::string soft_ball(const std::string& name, double radius, const std::string& material) {
  return R"({"name": ")" + name + R"(", "material": )" + material +
         R"(, "field": {"type": "soft_object", "potential": {"type": "murakami"},
           "distance": {"type": "lp_metric", "radii": [)" +
         std::to_string(radius) + "," + std::to_string(radius) + "," + std::to_string(radius) +
         R"(], "n": 2}}})";
}

// The largest difference of two pictures, and how many of their values differ by over 0.05.
std::pair<double, int> differences(const std::vector<float>& a, const std::vector<float>& b) {
  double most = 0;
  int many = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = std::fabs(double(a[i]) - b[i]);
    most = std::max(most, d);
    many += d > 0.05;
  }
  return {most, many};
}

// A ball of the same glass inside a glass ball: its surfaces part two media of the same index
// (POV-Ray's interior list: ratio 1), so the rays pass them straight and the picture is that of
// the outer ball alone. A ball of another glass there bends them: it shows.
TEST(InteriorsRender, AnInnerBallOfTheSameGlassIsInvisible) {
  const std::string dir = test::temp_dir("interiors_nested");
  const std::vector<float> alone = render_rgb(dir, "alone", soft_ball("outer", 10, kGlass));
  const std::vector<float> nested = render_rgb(
      dir, "nested", soft_ball("outer", 10, kGlass) + "," + soft_ball("inner", 5, kGlass));
  const auto [most, many] = differences(alone, nested);
  EXPECT_LT(most, 1e-3);
  EXPECT_EQ(many, 0);
  const std::vector<float> other = render_rgb(
      dir, "other",
      soft_ball("outer", 10, kGlass) + "," +
          soft_ball("inner", 5, R"({"transmit": 1, "ambient": 0, "diffuse": 0, "ior": 1.1})"));
  EXPECT_GT(differences(alone, other).second, 30);
}

// Two overlapping balls of the same glass, two objects: where the ray enters the second inside
// the first, and leaves the first inside the second, the media on both sides are the same glass
// (the overlap counts as the ball entered last), so the picture is that of their merge, one solid
// of that glass without inner surfaces. Only where the two surfaces meet within a pixel's
// footprint (the seam) may a ray step over one of them (secondary rays ignore that much of their
// start) and take the wrong media after it: 3 of the 1,200 pixels (the old tracer, which took
// every surface as one between glass and air, got 28).
TEST(InteriorsRender, OverlappingBallsOfTheSameGlassShowAsTheirMerge) {
  const std::string dir = test::temp_dir("interiors_overlap");
  const std::string a = R"({"type": "sphere", "center": [-1.2, 0, 0], "radius": 2.6})";
  const std::string b = R"({"type": "sphere", "center": [1.5, 0.5, 0.6], "radius": 2.2})";
  const std::vector<float> two =
      render_rgb(dir, "two",
                 std::string(R"({"name": "a", "material": )") + kGlass + R"(, "shape": )" + a +
                     "}," + R"({"name": "b", "material": )" + kGlass + R"(, "shape": )" + b + "}");
  const std::vector<float> merged =
      render_rgb(dir, "merged",
                 std::string(R"({"name": "ab", "csg": "merge", "material": )") + kGlass +
                     R"(, "operands": [{"shape": )" + a + R"(}, {"shape": )" + b + "}]}");
  const auto [most, many] = differences(two, merged);
  EXPECT_LE(many, 3 * 3);  // 3 values a pixel
  int close = 0;
  for (size_t i = 0; i < two.size(); ++i) close += std::fabs(double(two[i]) - merged[i]) < 1e-3;
  EXPECT_GE(close, int(two.size()) - 5 * 3);
}

}  // namespace interiors_test
}  // namespace softtrace

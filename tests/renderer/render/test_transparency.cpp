// Transparent materials (docs/math.md, "Transparency"): Snell's law and Fresnel's reflectance on
// their own; a ray through a glass ball (a soft object) entering, bending and leaving where the
// geometry says, total internal reflection inside it; shadows through filtered and transmitting
// balls tinted by each surface crossed; the trace-level limit on transmitted rays; the same bits
// for any thread count. The comparison with POV-Ray is tools/pov_finish.py (glass, filter_shadow,
// transmit).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/frame.h"
#include "render/shading.h"
#include "render/transparency.h"
#include "scene/scene.h"

namespace softtrace {
// Named, not anonymous: the unity build joins this file with others that have their own kInf.
namespace transparency_test {

constexpr double kInf = std::numeric_limits<double>::infinity();

double angle(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(a, b) / (length(a) * length(b)), -1.0, 1.0));
}

TEST(Transparency, RefractionFollowsSnell) {
  const Vec3 n{0, 0, 1};  // facing the ray
  for (double deg : {0.0, 20.0, 40.0, 70.0}) {
    const double a = deg * M_PI / 180;
    const Vec3 d{std::sin(a), 0, -std::cos(a)};
    Vec3 out;
    ASSERT_TRUE(refract(d, n, 1 / 1.5, out)) << deg;
    EXPECT_NEAR(length(out), 1, 1e-12);
    // sin(theta_t) = sin(theta_i) n_i / n_t, on the same side of the normal, bent towards it.
    EXPECT_NEAR(std::sin(angle(out, -n)), std::sin(a) / 1.5, 1e-12) << deg;
    EXPECT_GE(out.x, 0);
    EXPECT_LT(out.z, 0);
  }
  // From glass into air: beyond the critical angle asin(1/1.5) = 41.8 degrees the light
  // reflects whole.
  const auto leaves = [&](double deg) {
    const double a = deg * M_PI / 180;
    Vec3 out;
    return refract({std::sin(a), 0, -std::cos(a)}, n, 1.5, out);
  };
  EXPECT_TRUE(leaves(41.5));
  EXPECT_FALSE(leaves(42.0));
}

TEST(Transparency, FresnelReflectance) {
  // Head on: ((n - 1) / (n + 1))^2, 0.04 for glass; grazing: all of it; past the critical angle
  // (from glass, ratio 1/1.5): all of it.
  EXPECT_NEAR(fresnel_reflectance(1, 1.5), 0.04, 1e-12);
  EXPECT_NEAR(fresnel_reflectance(1, 1.33), std::pow(0.33 / 2.33, 2), 1e-12);
  EXPECT_GT(fresnel_reflectance(1e-4, 1.5), 0.999);
  EXPECT_EQ(fresnel_reflectance(0.5, 1 / 1.5), 1);
  // It rises with the angle of incidence.
  double last = 0;
  for (double c = 1; c > 0.05; c -= 0.05) {
    const double r = fresnel_reflectance(c, 1.5);
    EXPECT_GE(r, last);
    last = r;
  }
}

// A soft ball (murakami, radius 6, iso 0.5) at the origin.
const char* kBall = R"({
  "camera": {"eye": [0, -30, 0], "target": [0, 0, 0]},
  "lights": [],
  "objects": [{"name": "ball", "material": {"transmit": 0.9, "ior": 1.5},
               "field": {"type": "soft_object", "potential": {"type": "murakami"},
                         "distance": {"type": "lp_metric", "radii": [6, 6, 6], "n": 2}}}]})";

// The ball's surface radius, from a ray along the y axis.
double ball_radius(const TracedScene& rt) {
  const TraceHit h = rt.embree.intersect({{0, -30, 0}, {0, 1, 0}, 0, 1e-6}, 0, kInf);
  EXPECT_TRUE(h.hit);
  return 30 - h.t;
}

TEST(Transparency, ARayThroughAGlassBallLeavesWhereSnellSays) {
  const Scene scene = parse_scene(kBall, "ball.json");
  ASSERT_TRUE(scene.transparent);
  const TracedScene rt(scene, LipschitzMode::Local);
  const double r = ball_radius(rt);
  ASSERT_GT(r, 1);
  const ObjectTracer& tracer = rt.tracers[0];
  for (double b : {0.1, 0.5, 0.9}) {  // the ray's distance from the centre, in radii
    const Vec3 d{0, 1, 0};
    const Ray in{{b * r, -30, 0}, d, 0, 1e-6};
    const TraceHit enter = rt.embree.intersect(in, 0, kInf);
    ASSERT_TRUE(enter.hit);
    const Vec3 p1 = in.o + d * enter.t, n1 = tracer.normal(p1);
    EXPECT_NEAR(length(p1), r, 1e-4 * r);
    Vec3 d1;
    ASSERT_TRUE(refract(d, n1, 1 / 1.5, d1));
    // Inside: the first point of the solid's complement, where the chord of the refracted ray
    // ends: 2 r cos(theta_t) on, theta_t the refracted ray's angle to the inward normal.
    const double step = 1e-4 * scene.objects[0].bounds.diagonal();
    const Ray inside{p1 - n1 * step, d1, 0, 1e-6};
    const TraceHit leave = rt.embree.intersect(inside, 0, kInf, nullptr, 0);
    ASSERT_TRUE(leave.hit) << b;
    EXPECT_FALSE(leave.on_box_face);
    EXPECT_EQ(leave.object, 0);
    const Vec3 p2 = inside.o + d1 * leave.t;
    EXPECT_NEAR(length(p2), r, 1e-4 * r) << b;
    EXPECT_NEAR(length(p2 - p1), 2 * r * dot(d1, -n1), 1e-3 * r) << b;
    // Out again: the ray turns by 2 (theta_i - theta_t) in all.
    const Vec3 n2 = tracer.normal(p2);
    Vec3 d2;
    ASSERT_TRUE(refract(d1, -n2, 1.5, d2)) << b;
    const double theta_i = std::asin(b), theta_t = std::asin(b / 1.5);
    EXPECT_NEAR(angle(d, d2), 2 * (theta_i - theta_t), 1e-3) << b;
    // Without `inside` the ray from within finds the solid at once.
    EXPECT_LT(rt.embree.intersect(inside, 0, kInf).t, 1e-9 * r);
  }
}

TEST(Transparency, TotalInternalReflectionInsideTheBall) {
  const Scene scene = parse_scene(kBall, "ball.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  const double r = ball_radius(rt);
  // A chord 0.8 r from the centre meets the surface at asin(0.8) = 53 degrees, beyond glass's
  // critical angle: it cannot leave, and reflects to the next chord of the same length.
  const Ray ray{{0.8 * r, 0, 0}, {0, 1, 0}, 0, 1e-6};
  const TraceHit h = rt.embree.intersect(ray, 0, kInf, nullptr, 0);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 0.6 * r, 1e-4 * r);
  const Vec3 p = ray.o + ray.d * h.t, inward = -rt.tracers[0].normal(p);
  Vec3 out;
  EXPECT_FALSE(refract(ray.d, inward, 1.5, out));
  const Vec3 mirror = normalize(ray.d - inward * (2 * dot(ray.d, inward)));
  const Ray back{p + inward * (1e-4 * r), mirror, 0, 1e-6};
  const TraceHit again = rt.embree.intersect(back, 0, kInf, nullptr, 0);
  ASSERT_TRUE(again.hit);
  EXPECT_NEAR(again.t, 2 * 0.6 * r, 2e-4 * r);
}

// A ball over a white floor, lit straight from above (a directional light: the floor's cosine is
// 1 everywhere, so that its colour is the light that arrives).
std::string shadow_scene(const std::string& ball_material) {
  return R"({"camera": {"eye": [0, -40, 20], "target": [0, 0, 0]},
    "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 1}],
    "objects": [
      {"name": "floor", "material": {"color": [1, 1, 1]},
       "shape": {"type": "plane", "normal": [0, 0, 1], "distance": 0}},
      {"name": "ball", "material": )" +
         ball_material + R"(, "field": {"type": "soft_object", "translate": [0, 0, 8],
       "distance": {"type": "lp_metric", "radii": [6, 6, 6], "n": 2}}}]})";
}

// The floor's colour at (x, 0, 0), seen straight from above.
Vec3 floor_at(const Scene& scene, double x) {
  const TracedScene rt(scene, LipschitzMode::Local);
  const Ray ray{{x, 0.5, 1}, {0, 0, -1}, 0, 1e-4};
  const TraceHit hit = rt.embree.intersect(ray, 0, kInf);
  EXPECT_TRUE(hit.hit);
  EXPECT_EQ(hit.object, 0);
  RayWork work;
  return shade(scene, rt.tracers, rt.embree, ray, hit, work).color;
}

TEST(Transparency, ShadowsAreTintedByEachSurfaceCrossed) {
  // The shadow ray crosses the ball's surface twice: (f c + t)^2 of the light passes, per
  // channel; the open floor has all of it.
  const struct {
    const char* material;
    Vec3 passes;
  } cases[] = {
      {R"({"color": [0.2, 0.8, 0.3], "filter": 0.7})", {0.14 * 0.14, 0.56 * 0.56, 0.21 * 0.21}},
      {R"({"color": [0.2, 0.8, 0.3], "transmit": 0.6})", {0.36, 0.36, 0.36}},
      {R"({"color": [0.2, 0.8, 0.3], "filter": 0.5, "transmit": 0.25})",
       {0.35 * 0.35, 0.65 * 0.65, 0.4 * 0.4}},
      {R"({"color": [0.2, 0.8, 0.3]})", {0, 0, 0}},
  };
  for (const auto& c : cases) {
    const Scene scene = parse_scene(shadow_scene(c.material), "shadow.json");
    const Vec3 open = floor_at(scene, 30), under = floor_at(scene, 0);
    EXPECT_EQ(open.x, 1);
    EXPECT_EQ(open.y, 1);
    EXPECT_NEAR(under.x, c.passes.x, 1e-12) << c.material;
    EXPECT_NEAR(under.y, c.passes.y, 1e-12) << c.material;
    EXPECT_NEAR(under.z, c.passes.z, 1e-12) << c.material;
  }
}

TEST(Transparency, ShadowRaysStartAtTheHitNotAFootprintAboveIt) {
  // A clear primitive ball (exact hits) over the floor, lit at 45 degrees: the shadow ray from
  // floor point (x, 0, 0) passes the ball where |x - 8| < 4 sqrt 2. With a footprint of radius 1
  // a ray that started 1 above the floor would see that shadow moved by 1 in x; it starts at the
  // hit (docs/math.md §12.6), so a point 0.5 outside the outline is lit and 0.5 inside is not.
  const Scene scene = parse_scene(
      R"({"camera": {"eye": [0, -40, 20], "target": [0, 0, 0]},
      "lights": [{"type": "directional", "direction": [1, 0, -1], "intensity": 1}],
      "objects": [
        {"name": "floor", "material": {"color": [1, 1, 1]},
         "shape": {"type": "plane", "normal": [0, 0, 1], "distance": 0}},
        {"name": "ball", "material": {"transmit": 0.6},
         "shape": {"type": "sphere", "center": [0, 0, 8], "radius": 4}}]})",
      "slanted.json");
  ASSERT_TRUE(scene.transparent);
  const TracedScene rt(scene, LipschitzMode::Local);
  const auto floor_seen = [&](double x) {
    const Ray ray{{x, 0, 1}, {0, 0, -1}, 1, 0};
    const TraceHit hit = rt.embree.intersect(ray, 0, kInf);
    EXPECT_TRUE(hit.hit);
    EXPECT_EQ(hit.object, 0);
    RayWork work;
    return shade(scene, rt.tracers, rt.embree, ray, hit, work).color.x;
  };
  const double lit = std::sqrt(0.5), edge = 4 * std::sqrt(2.0);
  EXPECT_NEAR(floor_seen(8 - edge - 0.5), lit, 1e-12);
  EXPECT_NEAR(floor_seen(8 - edge + 0.5), 0.36 * lit, 1e-12);
  EXPECT_NEAR(floor_seen(8 + edge - 0.5), 0.36 * lit, 1e-12);
  EXPECT_NEAR(floor_seen(8 + edge + 0.5), lit, 1e-12);
}

// A clear ball (transmit 1: no colour of its own) in front of a flat background, seen through
// its centre, where the rays pass straight whatever the ior.
Vec3 through_centre(const std::string& material, int max_trace_level) {
  const Scene scene = parse_scene(
      R"({"camera": {"eye": [0, -30, 0], "target": [0, 0, 0]},
          "image": {"max_trace_level": )" +
          std::to_string(max_trace_level) + R"(}, "background": [0.2, 0.4, 0.6],
          "lights": [{"type": "ambient", "intensity": 1}],
          "objects": [{"name": "ball", "material": )" +
          material + R"(, "field": {"type": "soft_object",
            "distance": {"type": "lp_metric", "radii": [6, 6, 6], "n": 2}}}]})",
      "clear.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  const Ray ray{{0, -30, 0}, {0, 1, 0}, 0, 1e-6};
  const TraceHit hit = rt.embree.intersect(ray, 0, kInf);
  EXPECT_TRUE(hit.hit);
  RayWork work;
  return shade(scene, rt.tracers, rt.embree, ray, hit, work).color;
}

TEST(Transparency, TheTraceLevelLimitsRefractedRaysNotStraightOnes) {
  const Vec3 background{0.2, 0.4, 0.6}, black{0, 0, 0};
  const auto same = [](const Vec3& a, const Vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  };
  // ior 1: the transmitted rays continue the camera ray (POV-Ray's continued rays) and keep its
  // level; only the camera ray's level 1 must be below the limit.
  EXPECT_TRUE(same(through_centre(R"({"transmit": 1})", 1), black));
  EXPECT_TRUE(same(through_centre(R"({"transmit": 1})", 2), background));
  // ior 1.5: each refraction is a level; the ray that leaves the ball is level 3.
  EXPECT_TRUE(same(through_centre(R"({"transmit": 1, "ior": 1.5})", 2), black));
  EXPECT_TRUE(same(through_centre(R"({"transmit": 1, "ior": 1.5})", 3), background));
}

// Between two facing mirrors of reflection r lit by an ambient light alone, each surface shows 1
// and passes r of what its mirror ray sees: 1 + r + r^2 + ... up to max_trace_level terms. The
// k-th mirror ray weighs r^k (POV-Ray's ray weight) and is not traced below adc_bailout (1/255).
double between_mirrors(double r, int max_trace_level) {
  const std::string mirror = R"({"color": [1, 1, 1], "reflection": )" + std::to_string(r) + "}";
  const Scene scene = parse_scene(
      R"({"camera": {"eye": [0, -30, 2], "target": [0, 0, 2]},
          "image": {"max_trace_level": )" +
          std::to_string(max_trace_level) + R"(},
          "lights": [{"type": "ambient", "intensity": 1}],
          "objects": [
            {"name": "floor", "material": )" +
          mirror + R"(, "shape": {"type": "plane", "normal": [0, 0, 1], "distance": 0}},
            {"name": "ceiling", "material": )" +
          mirror + R"(, "shape": {"type": "plane", "normal": [0, 0, -1], "distance": -4}}]})",
      "mirrors.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  const Ray ray{{0, 0, 2}, normalize(Vec3{1, 0, -1}), 0, 1e-6};
  const TraceHit hit = rt.embree.intersect(ray, 0, kInf);
  EXPECT_TRUE(hit.hit);
  RayWork work;
  return shade(scene, rt.tracers, rt.embree, ray, hit, work).color.x;
}

TEST(Transparency, ChainsOfRaysStopWhereTheirWeightFallsBelowAdcBailout) {
  // r = 0.05: the second mirror ray would weigh 0.0025 < 1/255: 1 + r at any depth from 2.
  EXPECT_NEAR(between_mirrors(0.05, 2), 1.05, 1e-12);
  EXPECT_EQ(between_mirrors(0.05, 2), between_mirrors(0.05, 8));
  // r = 0.1: the second weighs 0.01 and is traced, the third 0.001 is not.
  EXPECT_NEAR(between_mirrors(0.1, 2), 1.1, 1e-12);
  EXPECT_NEAR(between_mirrors(0.1, 3), 1.11, 1e-12);
  EXPECT_EQ(between_mirrors(0.1, 3), between_mirrors(0.1, 8));
  // r = 0.5: every level up to the limit (0.5^7 = 0.0078 > 1/255).
  EXPECT_NEAR(between_mirrors(0.5, 8), 2 - std::pow(0.5, 7), 1e-12);
}

// A blend's materials each send their own mirror ray, weighed by their own reflectivity (POV-Ray
// shades each texture with the point's ray weight): at the top of two equal balls blended, half
// one component's and half the other's, a reflection of 0.006 on one of them sends a ray of weight
// 0.006 > 1/255 that adds 0.5 * 0.006 of the sky above; one ray weighed by the mixed reflectivity,
// 0.003 < 1/255, would not be traced.
double blended_top(double reflection) {
  const Scene scene = parse_scene(
      R"({"camera": {"eye": [0, -30, 10], "target": [0, 0, 0]},
          "background": [0.2, 0.4, 0.6],
          "lights": [{"type": "ambient", "intensity": 1}],
          "objects": [{"name": "blob", "field": {"type": "soft_blend", "children": [
            {"type": "soft_object", "potential": {"type": "murakami"}, "translate": [-1, 0, 0],
             "distance": {"type": "lp_metric", "radii": [2, 2, 2], "n": 2},
             "material": {"color": [1, 1, 1], "reflection": )" +
          std::to_string(reflection) + R"(}},
            {"type": "soft_object", "potential": {"type": "murakami"}, "translate": [1, 0, 0],
             "distance": {"type": "lp_metric", "radii": [2, 2, 2], "n": 2},
             "material": {"color": [0.5, 0.5, 0.5]}}]}}]})",
      "blend.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  const Ray ray{{0, 0.3, 10}, {0, 0, -1}, 0, 1e-6};
  const TraceHit hit = rt.embree.intersect(ray, 0, kInf);
  EXPECT_TRUE(hit.hit);
  RayWork work;
  return shade(scene, rt.tracers, rt.embree, ray, hit, work).color.x;
}

TEST(Transparency, EachBlendedMaterialWeighsItsOwnMirrorRay) {
  EXPECT_NEAR(blended_top(0.006) - blended_top(0), 0.5 * 0.006 * 0.2, 1e-7);
  // Above adc_bailout either way: 0.5 * 0.1 of the sky.
  EXPECT_NEAR(blended_top(0.1) - blended_top(0), 0.5 * 0.1 * 0.2, 1e-7);
}

TEST(TransparencyRender, SameBitsForOneAndTwoThreads) {
  const std::string dir = test::temp_dir("transparency_threads");
  {
    std::ofstream f(dir + "/glass.json");
    f << R"({"camera": {"eye": [1.5, -9, 4], "target": [0, 0, 0.4], "fov": 30},
      "lights": [{"type": "point", "position": [6, -7, 8], "intensity": 0.9},
                 {"type": "ambient", "intensity": 0.15}],
      "objects": [
        {"name": "ground", "material": {"color": [0.75, 0.75, 0.7]},
         "shape": {"type": "plane", "normal": [0, 0, 1], "distance": -1.9}},
        {"name": "glass", "material": {"color": [0.9, 0.95, 1], "transmit": 0.8, "filter": 0.1,
           "ior": 1.5, "reflection": 1, "fresnel": true, "conserve_energy": true, "phong": 0.8},
         "field": {"type": "soft_blend", "children": [
           {"type": "soft_object", "potential": {"type": "murakami"}, "translate": [-1, 0, 0],
            "distance": {"type": "lp_metric", "radii": [1.9, 1.9, 1.9], "n": 2}},
           {"type": "soft_object", "potential": {"type": "murakami"}, "translate": [1, 0.2, 0.1],
            "distance": {"type": "lp_metric", "radii": [1.8, 1.8, 1.8], "n": 2}}]}}]})";
  }
  const std::string base =
      "render " + dir + "/glass.json -q --width 48 --height 36 --spp 2 --aov steps ";
  ASSERT_EQ(test::run_softtrace(base + "--threads 1 -o " + dir + "/one.exr").status, 0);
  ASSERT_EQ(test::run_softtrace(base + "--threads 2 -o " + dir + "/two.exr").status, 0);
  const ImageFile one = read_image(dir + "/one.exr"), two = read_image(dir + "/two.exr");
  ASSERT_EQ(one.channels, two.channels);
  EXPECT_EQ(one.pixels, two.pixels);
  // Something of the ground shows through the glass: its pixels are not all one colour.
  const int r = one.channel("R");
  ASSERT_GE(r, 0);
  EXPECT_NE(one.at(24, 18, r), one.at(2, 2, r));
}

}  // namespace transparency_test
}  // namespace softtrace

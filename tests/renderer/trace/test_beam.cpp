// Beams: ObjectTracer::clear_depth certifies the approach to an object for every ray through a
// block of pixels. No ray of the block may meet the solid before the depth it returns, which a
// dense march along rays spread over the block (its corners, edges and inside) checks, for
// beams within beams as the frame nests them. The beams must also clear something: most of the
// empty rays of the view, and part of the way in front of the surfaces. (Thin and tiny parts, seen
// through beams, are test_no_holes.cpp's, against exact hits.)
#include <gtest/gtest.h>

#include <random>

#include "render/camera.h"
#include "scene/traced_objects.h"
#include "tracer_scenes.h"

namespace softtrace {
namespace {

using namespace tracer_scenes;

class Beams : public testing::TestWithParam<int> {};

TEST_P(Beams, NoRayMeetsTheSolidBeforeItsBeamsDepth) {
  const Scene scene = parse_scene(kScenes[GetParam()], "<test>");
  const SceneObject& obj = scene.objects[0];
  const ObjectTracer tr(trace_target(obj), LipschitzMode::Local);
  const Box& b = obj.bounds;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  constexpr int kW = 64, kH = 48;
  int rays = 0, met = 0, empty_cleared = 0, empty = 0, approach_cleared = 0;
  for (int view = 0; view < 6; ++view) {
    // A camera outside the box on a random side, looking at a random point of the box.
    const Vec3 dir = normalize({u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
    const Vec3 e = b.extent();
    const Vec3 target = b.lo + Vec3{u(rng) * e.x, u(rng) * e.y, u(rng) * e.z};
    const Camera cam{b.center() + dir * (0.6 + u(rng)) * b.diagonal(), target, {0, 0, 1}, 40};
    const ViewCamera camera(cam, kW, kH);
    for (int block = 0; block < 12; ++block) {
      // A 16-pixel block, one of its quarters, and one of that one's (as the frame nests them).
      int x = int(u(rng) * (kW / 16)) * 16, y = int(u(rng) * (kH / 16)) * 16, size = 16;
      double depth = 0;
      for (int level = 0; level < 3; ++level) {
        if (level > 0) {
          size /= 2;
          x += int(u(rng) * 2) * size;
          y += int(u(rng) * 2) * size;
        }
        TraceCounters work;
        depth = tr.clear_depth(camera.frustum(x, y, x + size, y + size), depth, work);
      }
      // Rays through its corners, edges' midpoints and random points inside it.
      std::vector<std::pair<double, double>> at;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) at.emplace_back(x + 0.5 * i * size, y + 0.5 * j * size);
      for (int i = 0; i < 8; ++i) at.emplace_back(x + u(rng) * size, y + u(rng) * size);
      for (const auto& [px, py] : at) {
        const Ray ray = camera.generate(px, py);
        double t0 = 0, t1 = 1e9;
        if (!clip_to_box(ray, b, t0, t1)) continue;
        ++rays;
        const double cos = dot(ray.d, normalize(target - cam.eye));
        const double clear_t = depth / cos;
        const double ref = reference_first_hit(tr, ray, t0, t1, 20000);
        if (std::isfinite(ref)) {
          ++met;
          ASSERT_GE(ref, clear_t * (1 - 1e-12))
              << "view " << view << ", pixel (" << px << ", " << py << "): the beam cleared to "
              << clear_t << " past the solid at " << ref;
          approach_cleared += clear_t > t0 + 0.1 * (ref - t0);
        } else {
          ++empty;
          empty_cleared += clear_t >= t1;
        }
      }
    }
  }
  std::printf(
      "%d rays: %d meet the solid (%d with a tenth of their approach cleared), %d empty "
      "(%d cleared)\n",
      rays, met, approach_cleared, empty, empty_cleared);
  EXPECT_GT(met, 50);
  EXPECT_GT(empty, 50);
  // The beams do clear (what they clear depends on the views; these are far below the counts).
  EXPECT_GT(empty_cleared, empty / 4);
  EXPECT_GT(approach_cleared, met / 10);
}

// Every scene but the blobs (which take no beams).
INSTANTIATE_TEST_SUITE_P(Scenes, Beams, testing::Range(0, kBlobs));

// The global mode is the baseline of every ray on its own, and polynomial blobs skip empty
// stretches per ray: neither takes beams.
TEST(Beams, NotForTheGlobalModeNorForPolynomialBlobs) {
  const Scene fig = parse_scene(kScenes[0], "<test>");
  const Scene blobs = parse_scene(
      R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"lp_metric","radii":[5,5,5],"n":2}},
        {"type":"soft_object","potential":{"type":"murakami"},"translate":[4,1,0],"distance":{"type":"lp_metric","radii":[3,6,2],"n":2}}]}}]})",
      "<test>");
  const ViewCamera camera(fig.camera, 64, 48);
  const Frustum fr = camera.frustum(0, 0, 16, 16);  // a corner: the background
  TraceCounters work;
  EXPECT_GT(
      ObjectTracer(trace_target(fig.objects[0]), LipschitzMode::Local).clear_depth(fr, 0, work), 0);
  EXPECT_EQ(
      ObjectTracer(trace_target(fig.objects[0]), LipschitzMode::Global).clear_depth(fr, 0, work),
      0);
  EXPECT_EQ(
      ObjectTracer(trace_target(blobs.objects[0]), LipschitzMode::Local).clear_depth(fr, 0, work),
      0);
}

}  // namespace
}  // namespace softtrace

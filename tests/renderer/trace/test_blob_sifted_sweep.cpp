// A camera list of a sum with blobs that only subtract (negative strengths) is sifted: it names
// the entries that may add (BlobBeam::adders), and a ray's sweep first asks whether their terms
// alone can reach iso on its way; where they cannot, the ray misses without taking the others'
// terms (first_hit_blobs, adders_below_iso). The answer must be the sweep's own to the bit, with
// the same work: a dimpled ball (pov:golfball's kind: one strong ball and 40 small negative balls
// across its surface) is traced through each block's list as sifted and as the same list
// unsifted.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>

#include "nested_beams.h"
#include "render/camera.h"
#include "same_march.h"
#include "scene/traced_objects.h"
#include "tracer_scenes.h"

namespace softtrace {
namespace {

using namespace tracer_scenes;

// A ball of radius 2.2 and strength 2 (its surface at 1.556), dimpled by 40 balls of radius 0.3
// and strength -0.4 whose centres lie at 1.65 from its centre, on a spiral.
Scene dimpled_ball() {
  std::string children = R"({"type":"soft_object","potential":{"type":"murakami"},"strength":2,)"
                         R"("distance":{"type":"lp_metric","radii":[2.2,2.2,2.2],"n":2}})";
  constexpr int kDimples = 40;
  for (int i = 0; i < kDimples; ++i) {
    const double z = 1 - (2 * i + 1.0) / kDimples, ring = std::sqrt(1 - z * z), a = 2.4 * i;
    children += R"(,{"type":"soft_object","potential":{"type":"murakami"},"strength":-0.4,)"
                R"("translate":[)" +
                std::to_string(1.65 * ring * std::cos(a)) + "," +
                std::to_string(1.65 * ring * std::sin(a)) + "," + std::to_string(1.65 * z) +
                R"(],"distance":{"type":"lp_metric","radii":[0.3,0.3,0.3],"n":2}})";
  }
  return parse_scene(
      R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)" + children + "]}}]}",
      "<test>");
}

TEST(BlobSiftedSweep, AddersFirstAnswerAsTheWholeSweep) {
  const Scene scene = dimpled_ball();
  const ObjectTracer tracer(trace_target(scene.objects[0]), LipschitzMode::Local);
  ASSERT_TRUE(tracer.blob_sum());
  const std::optional<BlobSum> sum = BlobSum::of(tracer.program());
  ASSERT_TRUE(sum && sum->size() > BlobSum::kListed && sum->subtracts());
  int adders = 0;
  for (int id = 0; id < sum->size(); ++id) adders += sum->adds(id);
  ASSERT_EQ(adders, 1);

  // The ball fills the middle of the view; its support's rim, beside the surface, a ring round it.
  constexpr int kW = 64, kH = 48;
  const ViewCamera camera(Camera{{0, -9, 1}, {0, 0, 0}, {0, 0, 1}, 40}, kW, kH);
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> u(0, 1);
  int rays = 0, hits = 0, sifted = 0, rim = 0;
  test::for_each_nested_beam(
      tracer, camera, kW, kH, [&](const BlobBeam(&lists)[3], int x4, int y4) {
        const BlobBeam& list = lists[2];
        // The adders are the entries of the one positive ball, in order.
        int expected = 0;
        for (size_t i = 0; i < list.entries.size(); ++i)
          if (sum->adds(list.entries[i].id)) {
            ASSERT_LT(expected, static_cast<int>(list.adders.size()));
            EXPECT_EQ(list.adders[expected++], static_cast<int32_t>(i));
          }
        EXPECT_EQ(expected, static_cast<int>(list.adders.size()));
        EXPECT_EQ(list.sifted, expected < static_cast<int>(list.entries.size()));
        sifted += list.sifted;
        BlobBeam whole = list;
        whole.sifted = false;
        for (int py = y4; py < y4 + 4; ++py)
          for (int px = x4; px < x4 + 4; ++px) {
            const Ray ray = camera.generate(px + u(rng), py + u(rng));
            TraceCounters ws, ww;
            const MarchResult hs = tracer.first_hit(ray, 0, 1e3, ws, Query::Nearest, 0, &list);
            const MarchResult hw = tracer.first_hit(ray, 0, 1e3, ww, Query::Nearest, 0, &whole);
            ++rays;
            hits += hw.hit;
            // Through the big ball's support (radius 2.2) but beside its surface (1.556).
            const double miss_by = length(cross(ray.d, ray.o)) / length(ray.d);
            rim += !hw.hit && miss_by > 1.6 && miss_by < 2.1;
            ASSERT_TRUE(test::same_march(hs, ws, hw, ww)) << "ray " << rays;
          }
      });
  if (HasFatalFailure()) return;
  // Hits through dimples and beside them, misses through the rim, and sifted lists among them.
  EXPECT_GT(hits, rays / 8);
  EXPECT_LT(hits, rays - rays / 8);
  EXPECT_GT(rim, 50);
  EXPECT_GT(sifted, 20);
}

}  // namespace
}  // namespace softtrace

// A cloud of balls' camera sweep takes its terms four list entries at a time (first_hit_blobs,
// BlobSum::ball_terms4); a sum with any other blob takes them one at a time (terms_of_one). The
// two must give the same hits to the bit, with the same work: the same cloud of balls is traced
// alone and with one small ellipsoid added inside its box, out of the camera's view, so that
// every block's list and every ray's way through the box are the same, and only the sweep's
// path differs.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>

#include "render/camera.h"
#include "same_march.h"
#include "scene/traced_objects.h"
#include "tracer_scenes.h"

namespace softtrace {
namespace {

using namespace tracer_scenes;

// 120 balls in [-12, 12]^3: Murakami's and Wyvill's potentials, some of negative strength.
std::string ball_cloud(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-12, 12), u(0, 1);
  std::string children;
  for (int i = 0; i < 120; ++i) {
    const std::string r = std::to_string(2 + 2.5 * u(rng));
    children += std::string(i ? "," : "") + R"({"type":"soft_object","potential":{"type":")" +
                (i % 5 == 2 ? "wyvill" : "murakami") + R"("},"strength":)" +
                (i % 9 == 4 ? "-0.4" : "1") + R"(,"translate":[)" + std::to_string(c(rng)) + "," +
                std::to_string(c(rng)) + "," + std::to_string(c(rng)) +
                R"(],"distance":{"type":"lp_metric","radii":[)" + r + "," + r + "," + r +
                R"(],"n":2}})";
  }
  return children;
}

Scene blob_scene(const std::string& children) {
  return parse_scene(
      R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)" + children + "]}}]}",
      "<test>");
}

// The same entries in the same order: the same distances and the same balls (the program may
// number the sum's children otherwise once the ellipsoid is among them).
bool same_entries(const BlobBeam& a, const BlobSum& sa, const BlobBeam& b, const BlobSum& sb) {
  if (a.entries.size() != b.entries.size()) return false;
  const auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  for (size_t i = 0; i < a.entries.size(); ++i) {
    const BlobBeam::Entry &ea = a.entries[i], &eb = b.entries[i];
    const BlobSum::Blob &ba = sa.blobs()[ea.id], &bb = sb.blobs()[eb.id];
    if (!same(ea.near, eb.near) || !same(ea.far, eb.far) || !same(ba.centre, bb.centre) ||
        !same(ba.inv_r2, bb.inv_r2) || !same(ba.c2, bb.c2) || !same(ba.c3, bb.c3))
      return false;
  }
  return true;
}

TEST(BlobSweepLanes, FourBallsAtOnceSweepAsOneAtATime) {
  std::mt19937_64 rng(27);
  const std::string balls = ball_cloud(rng);
  const Scene cloud = blob_scene(balls);
  const Box& box = cloud.objects[0].bounds;
  // The ellipsoid near the box's low corner, its support (radius 1.2 at most) well inside it.
  const Vec3 at = box.lo + Vec3{3, 3, 3};
  const Scene mixed =
      blob_scene(balls + R"(,{"type":"soft_object","potential":{"type":"murakami"},"translate":[)" +
                 std::to_string(at.x) + "," + std::to_string(at.y) + "," + std::to_string(at.z) +
                 R"(],"distance":{"type":"lp_metric","radii":[1.2,1,0.8],"n":2}})");
  const Box& mixed_box = mixed.objects[0].bounds;
  ASSERT_TRUE(box.lo.x == mixed_box.lo.x && box.lo.y == mixed_box.lo.y &&
              box.lo.z == mixed_box.lo.z && box.hi.x == mixed_box.hi.x &&
              box.hi.y == mixed_box.hi.y && box.hi.z == mixed_box.hi.z);
  const ObjectTracer four(trace_target(cloud.objects[0]), LipschitzMode::Local);
  const ObjectTracer one(trace_target(mixed.objects[0]), LipschitzMode::Local);
  ASSERT_TRUE(four.blob_sum() && one.blob_sum());
  const std::optional<BlobSum> sum_a = BlobSum::of(four.program()),
                               with_one = BlobSum::of(one.program());
  ASSERT_TRUE(sum_a && sum_a->all_balls());
  ASSERT_TRUE(with_one && !with_one->all_balls());

  // The cloud fills part of the view; the box's low corner is out of it.
  constexpr int kW = 64, kH = 48;
  const ViewCamera camera(Camera{{0, 0, 40}, {6, 6, 0}, {0, 1, 0}, 25}, kW, kH);
  std::uniform_real_distribution<double> u(0, 1);
  int rays = 0, hits = 0, short_lists = 0, long_lists = 0;
  BlobBeam a[3], b[3];
  const auto beams = [&](const Frustum& f, int level) {
    four.blob_beam(f, level ? &a[level - 1] : nullptr, &a[level]);
    one.blob_beam(f, level ? &b[level - 1] : nullptr, &b[level]);
    return same_entries(a[level], *sum_a, b[level], *with_one);
  };
  for (int y = 0; y < kH; y += 16)
    for (int x = 0; x < kW; x += 16) {
      ASSERT_TRUE(beams(camera.frustum(x, y, x + 16, y + 16), 0));
      for (int q = 0; q < 4; ++q) {
        const int x8 = x + (q & 1) * 8, y8 = y + (q >> 1) * 8;
        ASSERT_TRUE(beams(camera.frustum(x8, y8, x8 + 8, y8 + 8), 1));
        for (int k = 0; k < 4; ++k) {
          const int x4 = x8 + (k & 1) * 4, y4 = y8 + (k >> 1) * 4;
          ASSERT_TRUE(beams(camera.frustum(x4, y4, x4 + 4, y4 + 4), 2));
          const size_t listed = a[2].entries.size();
          short_lists += listed > 0 && listed < 4;
          long_lists += listed >= 4;
          for (int py = y4; py < y4 + 4; ++py)
            for (int px = x4; px < x4 + 4; ++px) {
              const Ray ray = camera.generate(px + u(rng), py + u(rng));
              TraceCounters wa, wb;
              const MarchResult ha = four.first_hit(ray, 0, 1e3, wa, Query::Nearest, 0, &a[2]);
              const MarchResult hb = one.first_hit(ray, 0, 1e3, wb, Query::Nearest, 0, &b[2]);
              ++rays;
              hits += ha.hit;
              ASSERT_TRUE(test::same_march(ha, wa, hb, wb)) << "ray " << rays;
            }
        }
      }
    }
  // Hits and misses (a miss sweeps its whole list, to the last four entries), and lists both
  // shorter than four (taken one at a time either way) and longer.
  EXPECT_GT(hits, rays / 8);
  EXPECT_LT(hits, rays - rays / 8);
  EXPECT_GT(long_lists, 20);
  std::printf("%d rays, %d hits, %d lists of 1-3 blobs, %d of 4 or more\n", rays, hits, short_lists,
              long_lists);
}

}  // namespace
}  // namespace softtrace

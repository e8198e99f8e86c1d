// Beams: ObjectTracer::clear_depth certifies the approach to an object for every ray through a
// block of pixels. No ray of the block may meet the solid before the depth it returns, which a
// dense march along rays spread over the block (its corners, edges and inside) checks, for
// beams within beams as the frame nests them. The beams must also clear something: most of the
// empty rays of the view, and part of the way in front of the surfaces. (Thin and tiny parts, seen
// through beams, are test_no_holes.cpp's, against exact hits.)
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>

#include "mixed_blob_cloud.h"
#include "nested_beams.h"
#include "render/camera.h"
#include "scene/traced_objects.h"
#include "trace/tracer_limits.h"
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

// A sum of polynomial blobs takes a list of blobs per block instead (ObjectTracer::blob_beam):
// every camera ray of a block, its list from the block's tile and quarters as the frame nests
// them, finds the same hit as the walk of the sum's BVH (within the refinement's tolerance: the
// ray sweeps its list, whose pieces are rounded otherwise than the walk's stretches), and the
// same normal at the walk's hit as the point query (ObjectTracer::normal with the list), and
// every blob with a term on the ray is on the list. The cloud mixes balls, rotated
// ellipsoids, capsules, a sheared capsule and negative strengths, some 40 of each, in a cube the
// camera sees from outside and from inside.
TEST(BlobBeams, EveryRayOfABlockHitsWhereTheBvhWalkDoes) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  const std::string children = mixed_blob_cloud(rng);
  const Scene scene = parse_scene(
      R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)" + children + "]}}]}",
      "<test>");
  const ObjectTracer tr(trace_target(scene.objects[0]), LipschitzMode::Local);
  ASSERT_TRUE(tr.blob_sum());
  const std::optional<BlobSum> sum = BlobSum::of(tr.program());
  ASSERT_TRUE(sum.has_value());
  const BlobSum& blobs = *sum;
  std::vector<BlobSum::Term> terms(blobs.max_terms());
  constexpr int kW = 96, kH = 64;
  int rays = 0, hits = 0, listed = 0, nested = 0, normals = 0, met = 0;
  double worst = 0;  // the largest |list.t - walk.t|, in tolerances
  for (const Vec3& eye : {Vec3{60, -80, 50}, Vec3{2, 3, 1}}) {
    const ViewCamera camera(Camera{eye, {0, 0, 0}, {0, 0, 1}, 50}, kW, kH);
    test::for_each_nested_beam(tr, camera, kW, kH, [&](const BlobBeam(&level)[3], int x4, int y4) {
      ASSERT_TRUE(level[2].valid);
      listed += static_cast<int>(level[2].entries.size());
      nested += level[2].entries.size() < level[0].entries.size();
      for (int py = y4; py < y4 + 4; ++py)
        for (int px = x4; px < x4 + 4; ++px) {
          const Ray ray = camera.generate(px + u(rng), py + u(rng));
          // Every blob with a term anywhere on the ray is on the block's list.
          for (int32_t id = 0; id < blobs.size(); ++id) {
            if (blobs.terms_of(&id, 1, ray.o, ray.d, 1e3, terms.data()) == 0) continue;
            bool on = false;
            for (const BlobBeam::Entry& e : level[2].entries) on = on || e.id == id;
            ASSERT_TRUE(on) << "blob " << id << ", ray " << rays;
            ++met;
          }
          TraceCounters a, b;
          const MarchResult walk = tr.first_hit(ray, 0, 1e3, a);
          const MarchResult list = tr.first_hit(ray, 0, 1e3, b, Query::Nearest, 0, &level[2]);
          ++rays;
          hits += walk.hit;
          ASSERT_EQ(list.hit, walk.hit) << "ray " << rays;
          // The ray sweeps its block's list (tracer_blobs.cpp): its pieces are one
          // stretch's over the whole way, rounded otherwise than the walk's stretches', and
          // both roots lie within the refinement's tolerance (kRefine of the footprint)
          // past the first crossing.
          if (walk.hit) {
            const double tol =
                tracer_limits::kRefine * tr.resolution(ray, std::max(list.t, walk.t)) * (1 + 1e-9);
            worst = std::max(worst, std::abs(list.t - walk.t) / tol);
            ASSERT_LE(std::abs(list.t - walk.t), tol)
                << "ray " << rays << ": " << list.t << " against the walk's " << walk.t;
          }
          if (walk.hit) {
            // The hit's normal from the list (TraceHit::blobs) is the point query's.
            const Vec3 p = ray.o + ray.d * walk.t;
            const Vec3 n_query = tr.normal(p), n_list = tr.normal(p, nullptr, &level[2]);
            ASSERT_EQ(n_list.x, n_query.x) << "ray " << rays;
            ASSERT_EQ(n_list.y, n_query.y) << "ray " << rays;
            ASSERT_EQ(n_list.z, n_query.z) << "ray " << rays;
            normals += length(n_query) > 0;
          }
        }
    });
  }
  EXPECT_GT(hits, rays / 10);
  EXPECT_LT(hits, rays);
  EXPECT_GT(normals, hits / 2);
  // The lists are short (the 4-pixel blocks' a few of the 160 blobs) and narrow as blocks shrink.
  // A capsule or ellipsoid is kept by its own outline, not its bounding sphere (a long capsule's
  // sphere meets most blocks): 12 per block here, 24 by the spheres alone.
  EXPECT_LT(listed, rays / 16 * 16);
  EXPECT_GT(nested, 0);
  std::printf("%d rays, %d blobs met, %d listed per block, worst root %.3g of the tolerance\n",
              rays, met, listed * 16 / rays, worst);
}

// A sum of at most BlobSum::kListed blobs takes a hit's normal from all its block's list, with no
// test of the entries' ranges (blob_gradient): the sum keeps the blobs that hold the point, as the
// point query does, so the normal is the query's to the bit. The tracer scenes' five blobs, seen
// from outside and from inside, through the blocks' lists of every level.
TEST(BlobBeams, AFewBlobsNormalFromTheListIsThePointQuerys) {
  const Scene scene = parse_scene(tracer_scenes::kScenes[tracer_scenes::kBlobs], "<test>");
  const ObjectTracer tr(trace_target(scene.objects[0]), LipschitzMode::Local);
  ASSERT_TRUE(tr.blob_sum());
  ASSERT_LE(tr.blob_count(), BlobSum::kListed);
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> u(0, 1);
  constexpr int kW = 64, kH = 48;
  int normals = 0, fewer = 0;
  for (const Vec3& eye : {Vec3{30, -40, 20}, Vec3{1, 2, 0.5}}) {
    const ViewCamera camera(Camera{eye, {0, 0, 0}, {0, 0, 1}, 60}, kW, kH);
    test::for_each_nested_beam(tr, camera, kW, kH, [&](const BlobBeam(&level)[3], int x4, int y4) {
      ASSERT_TRUE(level[2].valid);
      for (int py = y4; py < y4 + 4; ++py)
        for (int px = x4; px < x4 + 4; ++px) {
          const Ray ray = camera.generate(px + u(rng), py + u(rng));
          TraceCounters w;
          const MarchResult m = tr.first_hit(ray, 0, 1e3, w, Query::Nearest, 0, &level[2]);
          if (!m.hit) continue;
          const Vec3 p = ray.o + ray.d * m.t;
          const Vec3 n_query = tr.normal(p);
          for (const BlobBeam& list : level) {
            const Vec3 n_list = tr.normal(p, nullptr, &list);
            ASSERT_EQ(n_list.x, n_query.x) << "pixel " << px << ", " << py;
            ASSERT_EQ(n_list.y, n_query.y) << "pixel " << px << ", " << py;
            ASSERT_EQ(n_list.z, n_query.z) << "pixel " << px << ", " << py;
          }
          ++normals;
          fewer += level[2].entries.size() < size_t(tr.blob_count());
        }
    });
  }
  EXPECT_GT(normals, 1000);
  EXPECT_GT(fewer, 100);  // lists that leave some blobs out
}

}  // namespace
}  // namespace softtrace

// Unmet beams: a 4-pixel beam whose list of a lone blob sum holds no blob (EmbreeScene::unmet)
// answers its camera rays without the sum's search (EmbreeScene::intersect_unmet), and a pixel
// whose samples all miss is written as it is traced (frame.cpp's miss_pixel). Over a sparse cloud
// (most pixels background, as tools/blob_scene.py --meets 1 writes it), every ray of every unmet
// beam must get intersect()'s very answer: no hit, and the same counters (the steps AOV); and the
// frame's hit mask must be that of each pixel-centre ray traced alone, so neither shortcut may
// drop a pixel with a hit. The same holds over the cloud with a floor, a ball and a box beside it
// (the direct path with primitives): an unmet beam's ray gets the primitives' nearest hit as
// intersect() finds it, with the sum's miss before it counted the same.
//
// Passing rays: a beam whose list holds a few balls (EmbreeScene::passable) answers each ray that
// passes outside all of them (ObjectTracer::passes_listed_balls) as an unmet beam's, through
// EmbreeScene::intersect_passing. Such a ray must get intersect()'s answer and counters too, and
// none may be one that meets the sum.
//
// A block's rays answered together (EmbreeScene::unmet_rays, UnmetRays::answer, frame.cpp's
// unmet_pixel): for a lone sum, each ray of an unmet or passable beam must be answered exactly
// where intersect_unmet or intersect_passing answers it, with the same counters; beside
// primitives no beam is prepared so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/frame.h"
#include "scene/scene.h"
#include "sparse_ball_cloud.h"
#include "trace/primitive_trace.h"
#include "trace/unmet_rays.h"

namespace softtrace {
namespace {

constexpr double kUnmetFar = std::numeric_limits<double>::infinity();

// `n` balls at random (sparse_ball_cloud.h), seen from outside.
std::string unmet_sparse_cloud(int n) {
  return sparse_ball_cloud(
      n, 24, R"({"eye": [70, -95, 60], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 30})");
}

// The same cloud over a floor, with a ball beside it, a box among its blobs and a ball between it
// and the eye (the direct path with primitives: at most four beside the field, no Embree). The
// last one's rays stop short of the sum's box: the sum is searched only up to a primitive's hit.
std::string unmet_cloud_on_floor(int n) {
  std::string scene = unmet_sparse_cloud(n);
  const std::string primitives =
      R"(, {"shape": {"type": "plane", "distance": -21}},
      {"shape": {"type": "sphere", "center": [-27, 0, -14], "radius": 5}},
      {"shape": {"type": "box", "corner1": [12, 4, -21], "corner2": [19, 18, -8]}},
      {"shape": {"type": "sphere", "center": [35, -47, 30], "radius": 4}}]})";
  scene.replace(scene.size() - 2, 2, primitives);
  return scene;
}

bool same_unmet_counters(const TraceCounters& a, const TraceCounters& b) {
  return a.point_evals == b.point_evals && a.box_evals == b.box_evals &&
         a.refine_iterations == b.refine_iterations && a.give_ups == b.give_ups &&
         a.undecided == b.undecided && a.entered_box == b.entered_box;
}

// What a walk over every unmet beam's rays of a 128x96 frame saw.
struct UnmetWalk {
  int rays = 0, unmet_rays = 0, counted = 0;
  // Rays of passable beams; of them, those that meet the sum, those answered as unmet ones, and
  // those of these that counted stretches (entered the sum's box).
  int passable_rays = 0, passable_sum_hits = 0, passing_rays = 0, passing_counted = 0;
  int sum_hits = 0;  // every ray's hits on the sum (object 0)
  // Rays of blocks that EmbreeScene::unmet_rays prepared, and those UnmetRays::answer answered.
  int prepared_rays = 0, block_answers = 0;
  std::vector<int> unmet_hits;  // per object, the unmet rays' hits
};

// Every camera ray of every beam (the pixels' centres and a random point in each) through
// intersect(), and each ray of an unmet beam through intersect_unmet too: the same answer to the
// bit (none may be the sum's), and the same counters.
void walk_unmet_beams(const Scene& scene, const TracedScene& rt, UnmetWalk& walk) {
  const ObjectTracer* tracer = rt.tracers.tracer(0);
  ASSERT_TRUE(tracer && tracer->blob_sum());
  constexpr int kW = 128, kH = 96;
  const ViewCamera camera(scene.camera, kW, kH);
  const int objects = rt.tracers.size();
  walk.unmet_hits.assign(size_t(objects), 0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  // Per level, per object: a primitive has no depth and no list (frame.cpp's beam()).
  std::vector<double> depth(size_t(3 * objects), 0);
  std::vector<BlobBeam> lists(size_t(3 * objects));
  for (int ty = 0; ty < kH; ty += 16)
    for (int tx = 0; tx < kW; tx += 16) {
      // The frame's nesting (frame.cpp's beam()): the tile, a quarter, a quarter of that.
      for (int q = 0; q < 4; ++q)
        for (int k = 0; k < 4; ++k) {
          const int x8 = tx + (q & 1) * 8, y8 = ty + (q >> 1) * 8;
          const int x4 = x8 + (k & 1) * 4, y4 = y8 + (k >> 1) * 4;
          const int x[3] = {tx, x8, x4}, y[3] = {ty, y8, y4};
          for (int level = 0; level < 3; ++level) {
            const int size = 16 >> level;
            const Frustum fr = camera.frustum(x[level], y[level], x[level] + size, y[level] + size);
            TraceCounters work;
            const size_t at = size_t(level * objects), up = size_t((level - 1) * objects);
            depth[at] = tracer->clear_depth(fr, level ? depth[up] : 0, work);
            tracer->blob_beam(fr, level ? &lists[up] : nullptr, &lists[at], level == 2);
          }
          const size_t last = size_t(2 * objects);
          BeamClear beam{camera.frustum(x4, y4, x4 + 4, y4 + 4).forward, &depth[last],
                         &lists[last]};
          beam.unmet = rt.embree.unmet(beam);
          beam.passable = !beam.unmet && rt.embree.passable(beam);
          const bool unmet = beam.unmet, passable = beam.passable;
          UnmetRays together;
          const bool prepared = rt.embree.unmet_rays(beam, camera.eye(), &together);
          ASSERT_EQ(prepared, (unmet || passable) && objects == 1);
          for (int py = y4; py < y4 + 4; ++py)
            for (int px = x4; px < x4 + 4; ++px)
              for (int s = 0; s < 2; ++s) {  // the pixel's centre and a point inside it
                const Ray ray = camera.generate(px + (s ? u(rng) : 0.5), py + (s ? u(rng) : 0.5));
                const TraceHit full = rt.embree.intersect(ray, 0, kUnmetFar, &beam);
                ++walk.rays;
                walk.sum_hits += full.hit && full.object == 0;
                if (!unmet && !passable) continue;
                TraceHit hit;
                hit.hit = true;  // to be overwritten
                TraceCounters counters;
                counters.point_evals = -1;  // to be overwritten
                const bool answered = prepared && together.answer(ray, counters);
                walk.prepared_rays += prepared;
                walk.block_answers += answered;
                if (answered) {
                  ASSERT_FALSE(full.hit) << "pixel (" << px << ", " << py << ")";
                  ASSERT_TRUE(same_unmet_counters(counters, full.work))
                      << "pixel (" << px << ", " << py << "): box evaluations "
                      << counters.box_evals << " against intersect's " << full.work.box_evals;
                }
                if (passable) {
                  ++walk.passable_rays;
                  walk.passable_sum_hits += full.hit && full.object == 0;
                  const bool passing = rt.embree.intersect_passing(ray, beam, hit);
                  ASSERT_EQ(answered, prepared && passing) << "pixel (" << px << ", " << py << ")";
                  if (!passing) continue;
                  ++walk.passing_rays;
                  walk.passing_counted += full.work.box_evals > 0;
                } else {
                  ASSERT_TRUE(rt.embree.intersect_unmet(ray, beam, hit))
                      << "pixel " << px << ", " << py;
                  ASSERT_EQ(answered, prepared) << "pixel (" << px << ", " << py << ")";
                  ++walk.unmet_rays;
                }
                ASSERT_NE(full.object, 0) << "pixel (" << px << ", " << py
                                          << "): an unmet beam's ray meets the sum at " << full.t;
                ASSERT_EQ(hit.hit, full.hit) << "pixel (" << px << ", " << py << ")";
                ASSERT_EQ(hit.object, full.object) << "pixel (" << px << ", " << py << ")";
                ASSERT_EQ(std::memcmp(&hit.t, &full.t, sizeof hit.t), 0);
                ASSERT_EQ(std::memcmp(&hit.normal, &full.normal, sizeof hit.normal), 0);
                ASSERT_EQ(hit.on_box_face, full.on_box_face);
                ASSERT_EQ(hit.face, full.face);
                ASSERT_EQ(hit.blobs, nullptr);
                ASSERT_EQ(full.blobs, nullptr);
                ASSERT_TRUE(same_unmet_counters(hit.work, full.work))
                    << "pixel (" << px << ", " << py << "): box evaluations " << hit.work.box_evals
                    << " against intersect's " << full.work.box_evals;
                walk.counted += full.work.box_evals > 0;
                if (full.hit) ++walk.unmet_hits[size_t(full.object)];
              }
        }
    }
}

TEST(UnmetBeams, EveryRayGetsIntersectsAnswer) {
  const Scene scene = parse_scene(unmet_sparse_cloud(400), "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  ASSERT_FALSE(rt.embree.built());  // the direct path of a lone field
  UnmetWalk walk;
  walk_unmet_beams(scene, rt, walk);
  // Not vacuous: most rays are the background's and most of those are answered without the sum,
  // some of them after passing through its box (their steps counted); the cloud is seen.
  EXPECT_GT(walk.unmet_rays, walk.rays / 3);
  EXPECT_GT(walk.counted, walk.unmet_rays / 10);
  EXPECT_GT(walk.sum_hits, 20);
  // Most rays of passable beams pass between the balls; some meet them, and must not be taken so.
  EXPECT_GT(walk.passing_rays, walk.passable_rays / 2);
  EXPECT_GT(walk.passable_sum_hits, 20);
  EXPECT_GT(walk.passing_counted, walk.passing_rays / 10);
  // Every unmet ray and every passing one answered together too; the others of their blocks not.
  EXPECT_EQ(walk.block_answers, walk.unmet_rays + walk.passing_rays);
  EXPECT_EQ(walk.prepared_rays, walk.unmet_rays + walk.passable_rays);
}

TEST(UnmetBeams, BesidePrimitivesEveryRayGetsIntersectsAnswer) {
  const Scene scene = parse_scene(unmet_cloud_on_floor(60), "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  ASSERT_EQ(rt.tracers.size(), 5);
  ASSERT_FALSE(rt.embree.built());  // the direct path of a field and primitives
  UnmetWalk walk;
  walk_unmet_beams(scene, rt, walk);
  // Not vacuous: most rays are answered without the sum; of those, many meet the floor, and some
  // each ball and the box (so a skipped primitive shows, or a sum searched past the front ball's
  // hit: its box entered), some only after passing through the sum's box (their steps counted);
  // the cloud itself is seen by other beams.
  EXPECT_GT(walk.unmet_rays, walk.rays / 3);
  EXPECT_GT(walk.counted, walk.unmet_rays / 10);
  EXPECT_GT(walk.unmet_hits[1], walk.unmet_rays / 3);  // the floor
  EXPECT_GT(walk.unmet_hits[2], 50);                   // the ball
  EXPECT_GT(walk.unmet_hits[3], 50);                   // the box
  EXPECT_GT(walk.unmet_hits[4], 50);                   // the ball in front
  EXPECT_GT(walk.sum_hits, 20);
}

// Three positive balls about a negative one (pov:old_syntax's blob, a sum of at most kListed
// blobs, whose rays take their whole way at once), seen close up, and the sparse cloud with every
// fifth ball negative (more than kListed blobs: camera rays sweep their lists). A ball that only
// subtracts takes no bound in passing_balls (its terms' peaks are 0), so a beam whose list holds
// one is passable too: each of its passing rays must still get intersect()'s answer and counters.
std::string few_balls_with_a_subtracting_one() {
  std::string children;
  const double centres[4][3] = {
      {0.649519, -0.375, 0}, {-0.32476, 0.1875, 0.64952}, {-0.32476, 0.1875, -0.64952}, {0, 0, 0}};
  for (int i = 0; i < 4; ++i)
    children += std::string(i ? "," : "") +
                R"({"type": "soft_object", "potential": {"type": "murakami"}, "strength": )" +
                (i == 3 ? "-0.5" : "1") + R"(, "distance": {"type": "lp_metric", "radii": )" +
                (i == 3 ? "[0.6, 0.6, 0.6]" : "[1, 1, 1]") + R"(, "n": 2}, "translate": [)" +
                std::to_string(centres[i][0]) + "," + std::to_string(centres[i][1]) + "," +
                std::to_string(centres[i][2]) + "]}";
  return R"({"camera": {"eye": [0.3, -6, 0.2], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 37},
    "image": {"spp": 1},
    "lights": [{"type": "point", "position": [-15, -25, 30], "shadows": true}],
    "objects": [{"iso": 0.6, "field": {"type": "soft_blend", "children": [)" +
         children + "]}}]}";
}

std::string cloud_with_subtracting_balls(int n) {
  std::string scene = unmet_sparse_cloud(n);
  // Every fifth child's potential is given a negative strength (the others keep 1).
  const std::string potential = R"("potential": {"type": "murakami"},)";
  size_t at = 0;
  for (int i = 0; (at = scene.find(potential, at)) != std::string::npos; ++i) {
    at += potential.size();
    if (i % 5 == 0) scene.insert(at, R"( "strength": -1.5,)");
  }
  return scene;
}

// Walks `text`'s unmet beams (walk_unmet_beams checks each passing ray against intersect()) and
// checks the walk was not vacuous: its passable beams hold more than 200 rays, more than
// 1/`passing_share` of them pass, some meet the sum (and must not be passed), and some passing
// rays enter the sum's box.
void expect_passable_beams_walked(const std::string& text, int passing_share) {
  const Scene scene = parse_scene(text, "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  const ObjectTracer* tracer = rt.tracers.tracer(0);
  ASSERT_TRUE(tracer && tracer->blob_sum());
  UnmetWalk walk;
  walk_unmet_beams(scene, rt, walk);
  EXPECT_GT(walk.passable_rays, 200);
  EXPECT_GT(walk.passing_rays, walk.passable_rays / passing_share);
  EXPECT_GT(walk.passable_sum_hits, 20);
  EXPECT_GT(walk.passing_counted, walk.passing_rays / 10);
}

// Beams whose lists hold a negative ball are passable, and most of their rays pass.
TEST(UnmetBeams, ListsWithSubtractingBallsPassAsTheSearchAnswers) {
  for (const std::string& text :
       {few_balls_with_a_subtracting_one(), cloud_with_subtracting_balls(400)})
    expect_passable_beams_walked(text, 3);
}

// Capsules and ellipsoids (passing_balls' framed blobs): pov:sheared's blob (frames placed by
// matrices, one negative ellipsoid), a candle's (frames that only translate and scale, negative
// balls), both sums of at most kListed blobs, and a ring of 12 capsules and 12 balls (more than
// kListed: camera rays sweep their lists). Each passing ray of their passable beams must still get
// intersect()'s answer and counters.
std::string framed_blobs_scene(const std::string& camera, const std::string& children, double iso) {
  return R"({"camera": )" + camera + R"(, "image": {"spp": 1},
    "lights": [{"type": "point", "position": [8, -12, 14], "shadows": true}],
    "objects": [{"iso": )" +
         std::to_string(iso) + R"(, "field": {"type": "soft_blend", "children": [)" + children +
         "]}}]}";
}

std::string sheared_blob() {
  return framed_blobs_scene(
      R"({"eye": [0, -11, 6], "target": [0, 0, 0.5], "up": [0, 0, 1], "fov": 34.5})",
      R"({"type": "soft_object", "potential": {"type": "murakami"},
       "distance": {"type": "segment", "p0": [-2, 0, 0], "p1": [2, 0, 0], "radius": 0.9},
       "matrix": [[0.8137976813493738, 0.5130302149885031, -0.46984631039295416, -1.4095389311788626],
                  [-0.29619813272602386, 1.4095389311788626, 0.17101007166283433, 0.5130302149885031],
                  [0.275, 0.0, 0.47631397208144133, 1.1]]},
      {"type": "soft_object", "potential": {"type": "murakami"}, "strength": 1.2,
       "distance": {"type": "segment", "p0": [0, 0, -1.5], "p1": [0, 0, 1.5], "radius": 0.8},
       "matrix": [[1.3626411834226344, 0.5918355285391821, -0.33285989699489416, 0],
                  [-0.49596083075111147, 0.35523471239766546, 0.5999792953429918, 0],
                  [0.4648800879147694, -0.6408197576765439, 0.7636992484163723, 0]]},
      {"type": "soft_object", "potential": {"type": "murakami"},
       "distance": {"type": "lp_metric", "radii": [2.64, 1.32, 0.792], "n": 2},
       "translate": [2.238333837391833, -0.28259800492351705, -0.55],
       "rotate": {"axis": [0, 0, -1], "deg": 20}},
      {"type": "soft_object", "potential": {"type": "murakami"}, "strength": 1.5,
       "distance": {"type": "lp_metric", "radii": [1, 1, 1], "n": 2},
       "matrix": [[0.9396926207859084, 0.8118664537186229, 0.10260604299770061, -2.0072114086391024],
                  [-0.3420201433256687, 0.7686825491230741, 0.2819077862357725, 1.7947429791000802],
                  [0.44, 0.0, 1.1, -1.1]]},
      {"type": "soft_object", "potential": {"type": "murakami"}, "strength": -1.5,
       "distance": {"type": "lp_metric", "radii": [0.7, 0.7, 0.77], "n": 2},
       "translate": [0.4698463103929542, -0.17101007166283436, 0.22],
       "rotate": {"axis": [0, 0, -1], "deg": 20}})",
      0.5);
}

std::string candle_blob() {
  return framed_blobs_scene(
      R"({"eye": [0, -9, 5.5], "target": [0, 0, 2.2], "up": [0, 0, 1], "fov": 32})",
      R"({"type": "soft_object", "potential": {"type": "murakami"}, "strength": 2,
       "distance": {"type": "segment", "p0": [0, 0, 0], "p1": [0, 0, 3.2], "radius": 1.7}},
      {"type": "soft_object", "potential": {"type": "murakami"}, "strength": -2.5,
       "distance": {"type": "lp_metric", "radii": [1, 1, 1], "n": 2}, "translate": [0, 0, 3.55]},
      {"type": "soft_object", "potential": {"type": "murakami"}, "strength": 1.2,
       "distance": {"type": "lp_metric", "radii": [0.5, 0.5, 0.95], "n": 2},
       "translate": [0.95, -0.55, 2.35]},
      {"type": "soft_object", "potential": {"type": "murakami"}, "strength": 1.1,
       "distance": {"type": "segment", "p0": [-1.6, 0.4, 0.3], "p1": [-0.6, -0.8, 1.9],
                    "radius": 0.5}})",
      0.6);
}

std::string ring_of_capsules_and_balls() {
  std::string children;
  constexpr double kPi = 3.141592653589793;
  for (int i = 0; i < 12; ++i) {
    const double a0 = 2 * kPi * i / 12, a1 = 2 * kPi * (i + 1) / 12;
    const auto at = [](double a) {
      return "[" + std::to_string(4 * std::cos(a)) + "," + std::to_string(4 * std::sin(a)) + "," +
             std::to_string(0.3 * std::sin(3 * a)) + "]";
    };
    children += std::string(i ? "," : "") +
                R"({"type": "soft_object", "potential": {"type": "murakami"},
        "distance": {"type": "segment", "p0": )" +
                at(a0) + R"(, "p1": )" + at(a1) +
                R"(, "radius": 0.55}}, {"type": "soft_object", "potential": {"type": "murakami"},
        "strength": 0.8, "distance": {"type": "lp_metric", "radii": [0.8, 0.8, 0.8], "n": 2},
        "translate": )" +
                at(a0) + "}";
  }
  return framed_blobs_scene(
      R"({"eye": [0, -12, 9], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 30.5})", children, 0.4);
}

// Beams whose lists hold capsules or ellipsoids are passable, and many of their rays pass.
TEST(UnmetBeams, ListsOfCapsulesAndEllipsoidsPassAsTheSearchAnswers) {
  for (const std::string& text : {sheared_blob(), candle_blob(), ring_of_capsules_and_balls()})
    expect_passable_beams_walked(text, 4);
}

// A cloud cut by a floor alone, tilted (its world normal not the default's): intersect() and
// occluded() test the one unplaced plane directly (EmbreeScene's floor), intersect_unmet through
// the primitives' loop (nearest_primitive). Every unmet ray gets the same answer from both; every
// camera ray intersect()'s answer from the plane's and the sum's own tests (the sum searched up to
// the plane: blobs lie below it), and a shadow ray from each floor hit, or from just below it,
// occluded()'s.
TEST(UnmetBeams, OverAFloorAloneEveryRayGetsIntersectsAnswer) {
  std::string text = unmet_sparse_cloud(60);
  text.replace(text.size() - 2, 2,
               R"(, {"shape": {"type": "plane", "normal": [0.05, -0.1, 1], "distance": -8}}]})");
  const Scene scene = parse_scene(text, "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  ASSERT_EQ(rt.tracers.size(), 2);
  ASSERT_FALSE(rt.embree.built());
  UnmetWalk walk;
  walk_unmet_beams(scene, rt, walk);
  EXPECT_GT(walk.unmet_rays, walk.rays / 3);
  EXPECT_GT(walk.unmet_hits[1], walk.unmet_rays / 2);  // the floor
  EXPECT_GT(walk.sum_hits, 20);
  // Shadow rays towards the light, from the floor's hits lifted and sunk a little.
  const Primitive& floor = *rt.tracers.object(1).shape;
  const ObjectTracer* tracer = rt.tracers.tracer(0);
  const Vec3 to_light = -scene.lights[0].direction;
  const ViewCamera camera(scene.camera, 96, 72);
  int shadow_rays = 0, blocked = 0, below = 0, sum_hits = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit h = rt.embree.intersect(ray, 0, kUnmetFar);
      const PrimitiveHit p = first_hit(floor, ray, 0, kUnmetFar);
      TraceCounters field_work;
      const MarchResult m =
          tracer->first_hit(ray, 0, p.hit ? p.t : kUnmetFar, field_work, Query::Nearest);
      const bool on_sum = m.hit && (!p.hit || m.t < p.t);
      ASSERT_EQ(h.hit, p.hit || m.hit) << "pixel (" << x << ", " << y << ")";
      ASSERT_TRUE(same_unmet_counters(h.work, field_work)) << "pixel (" << x << ", " << y << ")";
      if (!h.hit) continue;
      ASSERT_EQ(h.object, on_sum ? 0 : 1) << "pixel (" << x << ", " << y << ")";
      const double t = on_sum ? m.t : p.t;
      ASSERT_EQ(std::memcmp(&h.t, &t, sizeof t), 0) << "pixel (" << x << ", " << y << ")";
      sum_hits += on_sum;
      if (on_sum) continue;
      ASSERT_EQ(std::memcmp(&h.normal, &floor.world_normal, sizeof h.normal), 0);
      for (const double lift : {1e-3, -1e-3, 0.0}) {
        const Ray shadow{ray.o + ray.d * h.t + h.normal * lift, to_light, 0, 0};
        TraceCounters work, own;
        const bool answer = rt.embree.occluded(shadow, 0, kUnmetFar, work);
        const bool plane = occludes(floor, shadow, 0, kUnmetFar);
        const bool sum = !plane && tracer->first_hit(shadow, 0, kUnmetFar, own, Query::Any).hit;
        ASSERT_EQ(answer, plane || sum) << "pixel (" << x << ", " << y << "), lift " << lift;
        ASSERT_TRUE(same_unmet_counters(work, own));
        ++shadow_rays;
        blocked += answer;
        below += plane;
      }
    }
  // Not vacuous: the sum is seen, the sunk rays meet the floor, some lifted ones the cloud.
  EXPECT_GT(sum_hits, 20);
  EXPECT_GT(shadow_rays, 3000);
  EXPECT_GT(below, shadow_rays / 4);
  EXPECT_GT(blocked - below, 20);
}

// UnmetRays::answer against first_hit_unlisted, the sum's clip and stretches as intersect_unmet
// asks them, over rays from one eye in every direction around the sum's box and clear depths
// before, inside and past it, and rays along a slab: the same counters. A second stretch, where
// rounding leaves the first short, needs t0 + (t1 - t0) to round below t1, so t0 below t1 / 2:
// the rays from an eye inside the box, with clear depths short of its sides, take some.
TEST(UnmetBeams, BlockAnswersAreTheUnlistedSearchs) {
  const Scene scene = parse_scene(unmet_sparse_cloud(40), "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  const ObjectTracer* tracer = rt.tracers.tracer(0);
  const Box& box = tracer->box();
  UnmetRays together;
  together.eye = {70, -95, 60};
  together.forward = normalize(box.center() - together.eye);
  together.box = box;
  together.lo_from_eye = box.lo - together.eye;
  together.hi_from_eye = box.hi - together.eye;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  const double far = length(box.extent()) + length(box.center() - together.eye);
  int answered = 0, missed = 0, cleared = 0;
  for (int i = 0; i < 200000; ++i) {
    together.depth = i % 3 == 0 ? 0 : far * u(rng);
    const Vec3 towards{box.lo.x - 5 + (box.extent().x + 10) * u(rng),
                       box.lo.y - 5 + (box.extent().y + 10) * u(rng),
                       box.lo.z - 5 + (box.extent().z + 10) * u(rng)};
    Vec3 d = normalize(towards - together.eye);
    if (i % 97 == 0) d.z = 0;  // a slab the ray runs along
    const Ray ray{together.eye, d, 0, 0};
    TraceCounters counters;
    counters.point_evals = -1;  // to be overwritten
    if (!together.answer(ray, counters)) {
      ASSERT_FALSE(dot(ray.d, together.forward) > 0) << "ray " << i;
      continue;
    }
    TraceCounters own;
    const double clear_to = together.depth / dot(ray.d, together.forward);
    const MarchResult m = tracer->first_hit_unlisted(ray, kUnmetFar, clear_to, own);
    ASSERT_FALSE(m.hit) << "ray " << i;
    ASSERT_TRUE(same_unmet_counters(counters, own))
        << "ray " << i << ": box evaluations " << counters.box_evals << " against " << own.box_evals
        << ", entered " << counters.entered_box << " against " << own.entered_box;
    ++answered;
    missed += !own.entered_box;
    cleared += own.entered_box && own.box_evals == 0;
  }
  // Not vacuous: rays beside the box, rays whose clear depth is past it, the others counted.
  EXPECT_GT(answered, 150000);
  EXPECT_GT(missed, 1000);
  EXPECT_GT(cleared, 1000);
  EXPECT_GT(answered - missed - cleared, 50000);

  together.eye = box.center() + box.extent() * 0.1;
  together.lo_from_eye = box.lo - together.eye;
  together.hi_from_eye = box.hi - together.eye;
  int inside = 0, stretched = 0;
  for (int i = 0; i < 20000; ++i) {
    together.depth = i % 5 == 0 ? 0 : 0.3 * box.extent().x * u(rng);
    const Vec3 d = normalize(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
    const Ray ray{together.eye, d, 0, 0};
    TraceCounters counters;
    if (!together.answer(ray, counters)) continue;
    TraceCounters own;
    const double clear_to = together.depth / dot(ray.d, together.forward);
    ASSERT_FALSE(tracer->first_hit_unlisted(ray, kUnmetFar, clear_to, own).hit) << "ray " << i;
    ASSERT_TRUE(same_unmet_counters(counters, own))
        << "ray " << i << " from inside: box evaluations " << counters.box_evals << " against "
        << own.box_evals;
    ++inside;
    stretched += own.box_evals > 1;
  }
  EXPECT_GT(inside, 5000);
  EXPECT_GT(stretched, 20);
}

// The frame (both shortcuts) against each pixel-centre ray traced alone: the same hit mask.
TEST(UnmetBeams, FrameHitMaskIsEachRaysOwn) {
  Scene scene = parse_scene(unmet_sparse_cloud(400), "<test>");
  const TracedScene rt(scene, LipschitzMode::Local);
  constexpr int kW = 128, kH = 96;
  const ViewCamera camera(scene.camera, kW, kH);
  Film film(kW, kH);
  ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, film, nullptr, nullptr));
  int hits = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const TraceHit alone = rt.embree.intersect(camera.generate(x + 0.5, y + 0.5), 0, kUnmetFar);
      const float depth = film.depth[size_t(y) * kW + x];
      ASSERT_EQ(alone.hit, depth < kUnmetFar) << "pixel (" << x << ", " << y << ")";
      ASSERT_EQ(film.rgba[(size_t(y) * kW + x) * 4 + 3], alone.hit ? 1.0f : 0.0f);
      hits += alone.hit;
    }
  EXPECT_GT(hits, 20);
  EXPECT_LT(hits, kW * kH / 2);
}

}  // namespace
}  // namespace softtrace

// Shadow lists (render/shadow_beams.h, ObjectTracer::shadow_beam): the shadow rays of a block of
// pixels towards a directional light take their stretches' blobs from the block's list, built as
// the frame builds it (the tile from the BVH, its quarters and theirs from their parents', over
// the points where the rays start). Every such ray must find what the walk of the sum's BVH finds:
// the same answer for a shadow ray (Query::Any; one with few blobs on its way takes it as one
// stretch, so its work is not the walk's, and less over all rays) and the same first hit, to the
// bit, with the same work (Query::Nearest). The cloud mixes balls, rotated ellipsoids, capsules, a
// sheared capsule and negative strengths; the points are camera hits on it and on a floor below it,
// lifted along the normal as shade() lifts them, and the light comes from above and from below
// (through the cloud onto the floor, and from the floor's side). And the frame, which traces a tile
// before shading it, gives every pixel the point query's normal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "cli_util.h"
#include "io/image_file.h"
#include "mixed_blob_cloud.h"
#include "render/camera.h"
#include "render/shadow_beams.h"
#include "scene/scene.h"
#include "scene/traced_objects.h"

namespace softtrace {
namespace {

// 60 balls of positive strength in [-20, 20]^3, Murakami's and Wyvill's, the floor seen between
// them: a sum whose blocks' lists pick blockers (BlobBeam::blockers). Hollowed, every third ball
// has a twin of the opposite strength at its place, which cancels it (the field is 0 there).
std::string positive_ball_cloud(std::mt19937_64& rng, bool hollowed = false) {
  std::uniform_real_distribution<double> c(-20, 20), u(0, 1);
  std::string children;
  for (int i = 0; i < 60; ++i) {
    const std::string r = std::to_string(5 + 3 * u(rng));
    const double strength = 0.8 + 0.4 * u(rng);
    const std::string at =
        std::to_string(c(rng)) + "," + std::to_string(c(rng)) + "," + std::to_string(c(rng));
    const auto ball = [&](double s) {
      return R"({"type":"soft_object","potential":{"type":")" +
             std::string(i % 3 ? "murakami" : "wyvill") + R"("},"strength":)" + std::to_string(s) +
             R"(,"translate":[)" + at + R"(],"distance":{"type":"lp_metric","radii":[)" + r + "," +
             r + "," + r + R"(],"n":2}})";
    };
    children += std::string(i ? "," : "") + ball(strength);
    if (hollowed && i % 3 == 0) children += "," + ball(-strength);
  }
  return children;
}

// A cloud (0: the mixed one, 1: positive_ball_cloud, 2: hollowed) over the floor z = -26 under
// one light, and the points where its shadow rays start: a camera's hits on the cloud (walked) or
// the floor, lifted along the normal as shade() lifts them. for_each_block builds the lists as the
// frame does (a tile's, each quarter's from it, each block's from that) and hands each 4-pixel
// block's list and points to `check`, block by block, as the frame orders them.
class CloudOverFloor {
 public:
  struct Lit {
    ShadowBeams::Point point;
    Vec3 origin;
  };
  CloudOverFloor(int cloud, const std::string& light, std::mt19937_64& rng, int finer = 1)
      : width((cloud ? 192 : 96) * finer),   // the balls' frame finer (a block's rays must pass
        height((cloud ? 128 : 64) * finer),  // near enough one ball's centre)
        rng_(rng),
        scene_(parse_scene(
            R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)" +
                (cloud == 0 ? mixed_blob_cloud(rng) : positive_ball_cloud(rng, cloud == 2)) +
                R"(]}}, {"shape": {"type": "plane", "distance": -26}}],
            "lights": [)" +
                light + "]}",
            "<test>")),
        objects_(traced_objects(scene_)),
        tracers_(objects_, LipschitzMode::Local),
        beams_(scene_, tracers_),
        camera_(Camera{{60, -80, 50}, {0, 0, -5}, {0, 0, 1}, cloud ? 40.0 : 60.0}, width, height) {}

  const Scene& scene() const { return scene_; }
  const ObjectTracer& tracer() const { return tracers_[0]; }
  const ShadowBeams& beams() const { return beams_; }

  // check(list, points): a block's list (its level-2 view's, of the scene's light `light`) and
  // its points. Stops at the first fatal failure.
  template <class Check>
  void for_each_block(Check&& check, int light = 0) {
    for_each_tile([&](const std::vector<ShadowBeams::Point>& points, const int(&start)[17],
                      const std::vector<Lit>(&by_block)[16]) {
      beams_.build(0, points.data(), 0, start[16], lists_);
      for (int q = 0; q < 4; ++q) {
        beams_.build(1, points.data(), start[q * 4], start[q * 4 + 4], lists_);
        for (int k = 0; k < 4; ++k) {
          const int b = q * 4 + k;
          beams_.build(2, points.data(), start[b], start[b + 1], lists_);
          const ShadowLists view = beams_.view(2, lists_);
          check(view.of(light), by_block[b]);
          if (::testing::Test::HasFatalFailure()) return;
        }
      }
    });
  }

  // check(points, start, by_block): a tile's points, block b's points[start[b], start[b + 1]),
  // which are by_block[b]'s. Stops at the first fatal failure.
  template <class Check>
  void for_each_tile(Check&& check) {
    for (int y = 0; y < height; y += 16)
      for (int x = 0; x < width; x += 16) {
        std::vector<Lit> by_block[16];
        for (int py = y; py < y + 16; ++py)
          for (int px = x; px < x + 16; ++px) {
            Lit l;
            if (!lit(camera_.generate(px + u_(rng_), py + u_(rng_)), &l)) continue;
            const int bx = (px - x) / 4, by = (py - y) / 4;
            by_block[((by >> 1) * 2 + (bx >> 1)) * 4 + (by & 1) * 2 + (bx & 1)].push_back(l);
          }
        // The tile's points block by block; a quarter's and a block's are ranges of them.
        points_.clear();
        int start[17] = {0};
        for (int b = 0; b < 16; ++b) {
          for (const Lit& l : by_block[b]) points_.push_back(l.point);
          start[b + 1] = static_cast<int>(points_.size());
        }
        check(points_, start, by_block);
        if (::testing::Test::HasFatalFailure()) return;
      }
  }

  const int width, height;

 private:
  // The camera hit of a ray, on the cloud (walked) or the floor z = -26, and its lifted point.
  bool lit(const Ray& ray, Lit* out) {
    TraceCounters w;
    const ObjectTracer& tr = tracer();
    const MarchResult m = tr.first_hit(ray, 0, 1e3, w);
    const double floor_t = ray.d.z < 0 ? (-26 - ray.o.z) / ray.d.z : -1;
    if (!m.hit && floor_t < 0) return false;
    const bool on_floor = !m.hit || (floor_t > 0 && floor_t < m.t);
    const Vec3 p = ray.o + ray.d * (on_floor ? floor_t : m.t);
    const Vec3 n = on_floor ? Vec3{0, 0, 1} : tr.normal(p);
    const double margin = 0.05 + 0.05 * u_(rng_);
    out->point = {p, margin};
    out->origin = p + n * (margin * u_(rng_));
    return true;
  }
  std::mt19937_64& rng_;
  std::uniform_real_distribution<double> u_{0, 1};
  const Scene scene_;
  const std::vector<TracedObject> objects_;
  const SceneTracers tracers_;
  const ShadowBeams beams_;
  const ViewCamera camera_;
  ShadowBeams::Lists lists_;
  std::vector<ShadowBeams::Point> points_;
};

TEST(ShadowBeams, EveryShadowRayOfABlockFindsWhatTheBvhWalkDoes) {
  std::mt19937_64 rng(11);
  long long with_work = 0, walk_work = 0;  // the held, undecided shadow rays'
  for (const int cloud : {0, 1})
    for (const char* direction : {"[1, 0.35, -1]", "[-0.3, 0.2, 1]"}) {
      CloudOverFloor floor(
          cloud, std::string(R"({"type": "directional", "direction": )") + direction + "}", rng);
      const ObjectTracer& tr = floor.tracer();
      ASSERT_TRUE(tr.blob_sum());
      ASSERT_TRUE(floor.beams().active());
      const Vec3 along = -floor.scene().lights[0].direction;
      const int kW = floor.width, kH = floor.height;
      int rays = 0, held = 0, blocked = 0, hits = 0, by_blocker = 0;
      long long listed = 0;
      floor.for_each_block([&](const BlobBeam* list,
                               const std::vector<CloudOverFloor::Lit>& block) {
        ASSERT_NE(list, nullptr);
        if (list[0].valid) listed += static_cast<long long>(list[0].entries.size());
        for (const CloudOverFloor::Lit& l : block) {
          const Ray ray{l.origin, along, 0, 0};
          double base;
          ++rays;
          // A block's list holds each of its rays; a block without one is clear (below) or sends
          // none into the cloud's box.
          if (list[0].valid) {
            ASSERT_TRUE(list[0].holds(ray, &base)) << "ray " << rays;
          }
          held += list[0].valid;
          TraceCounters a, b;
          const MarchResult walk = tr.first_hit(ray, 0, 1e3, a, Query::Any);
          const MarchResult with = tr.first_hit(ray, 0, 1e3, b, Query::Any, 0, &list[0]);
          ASSERT_EQ(with.hit, walk.hit) << "ray " << rays;
          // A clear list's ray is answered with no work (its soundness: ABlockWhoseRaysMeetNoBlob).
          if (list[0].clear) {
            ASSERT_EQ(b.evaluations(), 0) << "ray " << rays;
            TraceCounters c;
            ASSERT_FALSE(tr.first_hit(ray, 0, 1e3, c).hit) << "ray " << rays;
            continue;
          }
          if (!list[0].valid) {
            ASSERT_EQ(a.evaluations(), 0) << "ray " << rays;
          }
          // A ray a blocker decides costs one point and no stretch. Any other one the list holds
          // takes its way as one stretch (few blobs on it: the whole way's terms once): the
          // pieces are the walk's uncut by its stretches' ends, so their count may differ, but
          // the work over all rays is less (below).
          const bool decided = !list[0].blockers.empty() && with.hit && b.box_evals == 0 &&
                               b.point_evals == 1 && a.box_evals > 0;
          by_blocker += decided;
          if (!decided) {
            with_work += b.evaluations();
            walk_work += a.evaluations();
          }
          blocked += walk.hit;
          TraceCounters c, d;
          const MarchResult near = tr.first_hit(ray, 0, 1e3, c);
          const MarchResult near_with = tr.first_hit(ray, 0, 1e3, d, Query::Nearest, 0, &list[0]);
          ASSERT_EQ(near_with.hit, near.hit) << "ray " << rays;
          if (near.hit) {
            ASSERT_EQ(near_with.t, near.t) << "ray " << rays;
          }
          hits += near.hit;
        }
      });
      // Many rays go through a list (not a sixth of them from below the mixed cloud, whose
      // blocks with no blob on their lists are clear), and both answers occur.
      EXPECT_GT(held, rays / 8) << direction;
      EXPECT_GT(blocked, rays / 30) << direction;
      EXPECT_LT(blocked, rays * 9 / 10) << direction;
      EXPECT_EQ(hits, blocked) << direction;
      // The blocks' lists are a few of the 160 blobs.
      EXPECT_LT(listed, 16LL * (kW / 16) * (kH / 16) * 60) << direction;
      // Over the balls of positive strength, blockers decide many of the blocked rays (the floor's
      // under a ball).
      if (cloud == 1) {
        EXPECT_GT(by_blocker, blocked / 20) << direction;
      }
    }
  // One stretch for the whole way (few blobs on it) saves a held shadow ray's stretches after the
  // first: over all these rays, less work than the walk (printed: the fraction).
  std::printf("held shadow rays' work: %lld with lists, %lld walked\n", with_work, walk_work);
  EXPECT_LT(with_work * 10, walk_work * 9);
}

// A block whose prism misses the sum's box, or whose list holds no blob (or whose parent's does
// either), is clear: its shadow rays are answered "no hit" with no trace at all (BlobBeam::clear),
// which is sound only if no ray from within the margin of any of its points towards the light
// meets a blob's support. Every such ray of every clear block, from its point's lifted origin and
// from the edge of its margin ball in random directions, must find nothing by the BVH walk
// (Query::Nearest, the whole way), and where it enters the box the field must be 0 all along its
// way there (sampled every 0.1: a blob's support it crossed would show). Clear blocks must occur
// beside blocks that are not (whose rays EveryShadowRayOfABlockFindsWhatTheBvhWalkDoes checks),
// and some of them inside the box's shadow (their lists held no blob).
TEST(ShadowBeams, ABlockWhoseRaysMeetNoBlobIsClear) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int in_box = 0;  // clear rays that enter the box: their blocks' lists held no blob
  for (const int cloud : {0, 1})
    for (const char* direction : {"[1, 0.35, -1]", "[-0.3, 0.2, 1]", "[0.2, -1, -0.4]"}) {
      CloudOverFloor floor(
          cloud, std::string(R"({"type": "directional", "direction": )") + direction + "}", rng);
      const ObjectTracer& tr = floor.tracer();
      const Vec3 along = -floor.scene().lights[0].direction;
      const Box& box = floor.scene().objects[0].bounds;
      int clear = 0, listed = 0, rays = 0;
      floor.for_each_block(
          [&](const BlobBeam* list, const std::vector<CloudOverFloor::Lit>& block) {
            if (block.empty()) return;
            if (!list[0].clear) {
              ++listed;
              return;
            }
            ++clear;
            for (const CloudOverFloor::Lit& l : block) {
              Vec3 edge{u(rng), u(rng), u(rng)};
              edge = edge / length(edge) * l.point.margin;
              for (const Vec3& o : {l.origin, l.point.p + edge}) {
                TraceCounters w;
                const Ray ray{o, along, 0, 0};
                const MarchResult walk = tr.first_hit(ray, 0, 1e3, w);
                ASSERT_FALSE(walk.hit) << "a clear block's ray from " << o.x << ", " << o.y << ", "
                                       << o.z << " meets the cloud at " << walk.t;
                ++rays;
                double t0 = 0, t1 = 1e3;
                if (!clip_to_box(ray, box, t0, t1)) continue;
                ++in_box;
                for (double t = t0; t <= t1; t += 0.1) {
                  const Vec3 p = o + along * t;
                  ASSERT_EQ(tr.eval(p, nullptr), 0.0)
                      << "a clear block's ray from " << o.x << ", " << o.y << ", " << o.z
                      << " meets a blob's support at " << p.x << ", " << p.y << ", " << p.z;
                }
              }
            }
          });
      EXPECT_GT(clear, 100) << cloud << direction;
      EXPECT_GT(listed, 50) << cloud << direction;
      EXPECT_GT(rays, 2000) << cloud << direction;
    }
  std::printf("clear rays inside the cloud's box: %d\n", in_box);
  EXPECT_GT(in_box, 100);
}

// A shut block (BlobBeam::shut) answers its shadow rays "blocked", with blocked_by's work (one
// point, no stretch), without blocked_by's term: right only if blocked_by would have decided every
// such ray. Every ray of every shut block, from its lifted origin and from random points of the
// block's prism between its depths z0 and z1 with random footprints, must give the same answer and
// work through the list as through the same list unshut, and the walk with no list must find the
// cloud in its way. Shut blocks must be many over the positive balls; the mixed cloud's negative
// blobs leave none, and over the hollowed balls only the blocks whose lists hold no negative twin
// are shut (a negative term could hollow the ball, as there: the walk would show it).
TEST(ShadowBeams, EveryRayOfAShutBlockIsBlocked) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0, 1);
  int all_shut = 0, all_decided = 0;
  for (const int cloud : {0, 1, 2})
    for (const char* direction : {"[1, 0.35, -1]", "[-0.3, 0.2, 1]", "[0.2, -1, -0.4]"}) {
      CloudOverFloor floor(
          cloud, std::string(R"({"type": "directional", "direction": )") + direction + "}", rng);
      const ObjectTracer& tr = floor.tracer();
      const Vec3 along = -floor.scene().lights[0].direction;
      int shut = 0, with_blockers = 0, decided = 0, rays = 0;
      floor.for_each_block(
          [&](const BlobBeam* list, const std::vector<CloudOverFloor::Lit>& block) {
            with_blockers += !list[0].blockers.empty() && !block.empty();
            if (!list[0].shut) return;
            ++shut;
            BlobBeam unshut = list[0];
            unshut.shut = false;
            const ShadowPrism& p = list[0].prism;
            std::vector<Ray> tried;
            for (const CloudOverFloor::Lit& l : block) tried.push_back({l.origin, along, 0, 0});
            for (int i = 0; i < 8; ++i) {
              const double x = p.x0 + (p.x1 - p.x0) * u(rng), y = p.y0 + (p.y1 - p.y0) * u(rng),
                           z = p.z0 + (p.z1 - p.z0) * u(rng);
              tried.push_back({p.origin + p.u * x + p.v * y + p.along * z, along, 0.01 * u(rng),
                               0.002 * u(rng)});
            }
            for (size_t i = 0; i < tried.size(); ++i) {
              const Ray& ray = tried[i];
              TraceCounters a, b, c;
              const MarchResult with = tr.first_hit(ray, 0, 1e3, a, Query::Any, 0, &list[0]);
              const MarchResult without = tr.first_hit(ray, 0, 1e3, b, Query::Any, 0, &unshut);
              ASSERT_EQ(with.hit, without.hit) << "ray " << rays;
              ASSERT_EQ(a.point_evals, b.point_evals) << "ray " << rays;
              ASSERT_EQ(a.box_evals, b.box_evals) << "ray " << rays;
              ASSERT_EQ(a.entered_box, b.entered_box) << "ray " << rays;
              const bool own = i < block.size();
              if (own) {
                // The block's own rays are all blocked, each by one point.
                ASSERT_TRUE(with.hit) << "ray " << rays;
                ASSERT_EQ(a.evaluations(), 1) << "ray " << rays;
                ASSERT_TRUE(tr.first_hit(ray, 0, 1e3, c, Query::Any).hit) << "ray " << rays;
              }
              decided += with.hit && a.evaluations() == 1;
              ++rays;
            }
          });
      if (cloud == 1) {
        EXPECT_GT(shut, 5) << direction;
        EXPECT_GT(shut, with_blockers / 4) << direction;
        all_shut += shut;
        all_decided += decided;
      } else if (cloud == 0) {
        EXPECT_EQ(shut, 0) << direction;
      }
    }
  // The floor's blocks under the balls, and the balls' own (133 and 3,192 when written).
  EXPECT_GT(all_shut, 100);
  EXPECT_GT(all_decided, 2000);
}

// A tile's or a quarter's list that one of its blockers shuts is lent to its blocks, which build
// none of their own (ShadowBeams::shut_and_lend): right only if it decides every ray the block's
// own list would, with the same answer and work. A block's list is lent where its rectangle is
// wider than the balls about the block's points; for each such block, its own list (from the BVH
// over its own prism, with its own blockers) is built beside it, and every own ray must be
// blocked by one point through the lent list, as by the walk and, where the own list is shut,
// with that list's work. Lent blocks must be many over the positive balls, under the three lights.
TEST(ShadowBeams, ABlockOfAShutTileOrQuarterTakesItsList) {
  std::mt19937_64 rng(31);
  int lent = 0, own_shut = 0, rays = 0;
  for (const char* direction : {"[1, 0.35, -1]", "[-0.3, 0.2, 1]", "[0.2, -1, -0.4]"}) {
    // Finer still: a quarter or a tile shut by one ball is a small part of its shadow.
    CloudOverFloor floor(
        1, std::string(R"({"type": "directional", "direction": )") + direction + "}", rng, 3);
    const ObjectTracer& tr = floor.tracer();
    const Vec3 along = -floor.scene().lights[0].direction;
    floor.for_each_block([&](const BlobBeam* list, const std::vector<CloudOverFloor::Lit>& block) {
      if (block.empty() || !list[0].valid) return;
      const ShadowPrism& p = list[0].prism;
      // The rectangle and depths of the balls about the block's points, as build_prism takes
      // them (from the tile's origin, which every level shares).
      ShadowPrism own = p;
      own.x0 = own.y0 = own.z0 = 1e300;
      own.x1 = own.y1 = own.z1 = -1e300;
      for (const CloudOverFloor::Lit& l : block) {
        const Vec3 q = l.point.p - p.origin;
        const double m = l.point.margin * (1 + 1e-9);
        const double x = dot(q, p.u), y = dot(q, p.v), z = dot(q, p.along);
        own.x0 = std::min(own.x0, x - m), own.x1 = std::max(own.x1, x + m);
        own.y0 = std::min(own.y0, y - m), own.y1 = std::max(own.y1, y + m);
        own.z0 = std::min(own.z0, z - m), own.z1 = std::max(own.z1, z + m);
      }
      const double span = (own.x1 - own.x0) + (own.y1 - own.y0);
      if (!((p.x1 - p.x0) + (p.y1 - p.y0) > span * (1 + 1e-6))) return;  // the block's own list
      ++lent;
      ASSERT_TRUE(list[0].shut);
      BlobBeam mine;
      tr.shadow_beam(own, nullptr, &mine);
      ASSERT_TRUE(mine.valid);
      tr.shadow_blockers(&mine);
      own_shut += mine.shut;
      for (const CloudOverFloor::Lit& l : block) {
        const Ray ray{l.origin, along, 0, 0};
        TraceCounters a, b, c;
        const MarchResult with = tr.first_hit(ray, 0, 1e3, a, Query::Any, 0, &list[0]);
        const MarchResult alone = tr.first_hit(ray, 0, 1e3, b, Query::Any, 0, &mine);
        ASSERT_TRUE(with.hit) << "ray " << rays;
        ASSERT_EQ(a.evaluations(), 1) << "ray " << rays;
        ASSERT_TRUE(tr.first_hit(ray, 0, 1e3, c, Query::Any).hit) << "ray " << rays;
        ASSERT_TRUE(alone.hit) << "ray " << rays;
        if (mine.shut) {
          ASSERT_EQ(a.point_evals, b.point_evals) << "ray " << rays;
          ASSERT_EQ(a.box_evals, b.box_evals) << "ray " << rays;
        }
        ++rays;
      }
    });
  }
  std::printf("lent blocks: %d (%d shut by their own lists), their rays: %d\n", lent, own_shut,
              rays);
  EXPECT_GT(lent, 1000);
  EXPECT_GT(own_shut, lent / 2);
}

// The shadow rays of a block towards a point or spot light converge on its position: their list
// is the pyramid's from the light through the block's points (BlobBeam::toward), and each ray
// finds its stretches' blobs by minus its distance from the light. Every such ray must find what
// the walk finds, to the bit (a list missing a blob that shadows a lit point, or one read on the
// wrong axis, changes answers or work), and a ray that leaves the pyramid's sense (past the light,
// or in another direction) is not held. Lights above the cloud, under it and beside it
// (a spot), over the mixed cloud and the positive one.
TEST(ShadowBeams, EveryShadowRayTowardsAPointLightFindsWhatTheBvhWalkDoes) {
  std::mt19937_64 rng(23);
  long long with_work = 0, walk_work = 0;  // the held, undecided shadow rays'
  const char* lights[] = {
      R"({"type": "point", "position": [30, -20, 60]})",
      R"({"type": "point", "position": [3, 2, -23]})",
      (R"({"type": "spot", "position": [-70, -40, 10], "point_at": [0, 0, -10], "radius": 40,)"
       R"( "falloff": 60})"),  // one light in two lines, in parentheses for clang's warning
      // Two: the second's lists (each light's pyramids are the tile's own).
      R"({"type": "point", "position": [30, -20, 60]}, {"type": "point", "position": [-40, 10, 50]})"};
  for (const int cloud : {0, 1})
    for (const char* light : lights) {
      const int which = light == lights[3] ? 1 : 0;
      CloudOverFloor floor(cloud, light, rng);
      const ObjectTracer& tr = floor.tracer();
      ASSERT_TRUE(tr.blob_sum());
      ASSERT_TRUE(floor.beams().active());
      const Light& l = floor.scene().lights[which];
      const int kW = floor.width, kH = floor.height;
      int rays = 0, held = 0, blocked = 0, by_blocker = 0;
      long long listed = 0;
      floor.for_each_block(
          [&](const BlobBeam* list, const std::vector<CloudOverFloor::Lit>& block) {
            ASSERT_NE(list, nullptr);
            if (list[0].valid) {
              ASSERT_TRUE(list[0].toward);
              listed += static_cast<long long>(list[0].entries.size());
            }
            for (const CloudOverFloor::Lit& p : block) {
              LightArrival at;
              if (!light_arrival(l, p.point.p, p.origin, at)) continue;
              const Ray ray{p.origin, at.to_light, 0, 0};
              ++rays;
              double base;
              if (list[0].valid) {
                ASSERT_TRUE(list[0].holds(ray, &base, at.distance)) << "ray " << rays;
                // Not past the light, nor in another direction.
                EXPECT_FALSE(list[0].holds(ray, &base, at.distance * 1.01)) << "ray " << rays;
                const Ray off{p.origin, normalize(at.to_light + Vec3{1e-6, 0, 0}), 0, 0};
                EXPECT_FALSE(list[0].holds(off, &base, at.distance)) << "ray " << rays;
              }
              held += list[0].valid;
              for (const Query query : {Query::Any, Query::Nearest}) {
                TraceCounters a, b;
                const MarchResult walk = tr.first_hit(ray, 0, at.distance, a, query);
                const MarchResult with = tr.first_hit(ray, 0, at.distance, b, query, 0, &list[0]);
                ASSERT_EQ(with.hit, walk.hit) << "ray " << rays;
                if (query == Query::Any) blocked += walk.hit;
                // A ray a blocker decides costs one point and no stretch. Any other shadow ray
                // the list holds takes its way as one stretch (few blobs on it), less work over
                // all rays than the walk's stretches (below); a nearest hit the same stretches as
                // the walk, to the bit.
                const bool decided = query == Query::Any && !list[0].blockers.empty() && with.hit &&
                                     b.box_evals == 0 && b.point_evals == 1 && a.box_evals > 0;
                by_blocker += decided;
                if (decided) continue;
                if (query == Query::Any && list[0].valid) {
                  with_work += b.evaluations();
                  walk_work += a.evaluations();
                  continue;
                }
                if (walk.hit) {
                  ASSERT_EQ(with.t, walk.t) << "ray " << rays;
                }
                ASSERT_EQ(b.evaluations(), a.evaluations()) << "ray " << rays;
              }
            }
          },
          which);
      // Most rays go through a list, both answers occur, and the lists are short.
      EXPECT_GT(held, rays / 2) << light;
      EXPECT_GT(blocked, rays / 30) << light;
      EXPECT_LT(blocked, rays * 9 / 10) << light;
      EXPECT_LT(listed, 16LL * (kW / 16) * (kH / 16) * 40) << light;
      // Over the balls of positive strength, with the light above them, blockers decide many of
      // the blocked rays (the floor's under a ball).
      if (cloud == 1 && light == lights[0]) {
        EXPECT_GT(by_blocker, blocked / 20) << light;
      }
    }
  // One stretch for the whole way (few blobs on it) saves a held shadow ray's stretches after the
  // first: over all these rays, less work than the walk (printed: the fraction).
  std::printf("held shadow rays' work: %lld with lists, %lld walked\n", with_work, walk_work);
  EXPECT_LT(with_work * 10, walk_work * 9);
}

// A blocker is certified by its own potential only where no blob of the list can take from the
// field: a ball cancelled by a ball of negative strength at the same place (the field is 0 there)
// blocks no ray, and one beside a positive ball does; for a directional light and a point light.
// `n` small balls far from the origin (x >= 100), each after a comma: they fill a sum past
// ShadowBeams::kFewBlobs, below which it takes no lists, and meet no ray near the z axis.
std::string far_balls(int n) {
  std::string out;
  for (int i = 0; i < n; ++i)
    out += R"(,{"type":"soft_object","potential":{"type":"murakami"},"translate":[)" +
           std::to_string(100 + 10 * i) +
           R"(,0,0],"distance":{"type":"lp_metric",)"
           R"("radii":[1,1,1],"n":2}})";
  return out;
}

// A tile whose points' balls all lie beside the sum's box, seen along the light, is clear, and one
// of whose balls reaches into it is not: the tile's first test bounds its points by their box in
// world space (ShadowBeams::misses_boxes), which must clear only what the balls' own prism would
// (a margin left out of that bound would clear the second). The light comes from straight above
// and from straight below (the box's shadow is then its rectangle); the points lie beyond it,
// beside its face x = hi.x, the last one's ball 0.1 inside the face's plane, or 0.1 beside it.
TEST(ShadowBeams, ATileBesideTheBoxIsClearOnlyWhereItsBallsMissIt) {
  for (const char* direction : {"[0, 0, -1]", "[0, 0, 1]"}) {
    const Scene scene =
        parse_scene(R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)"
                    R"({"type":"soft_object","potential":{"type":"murakami"},)"
                    R"("distance":{"type":"lp_metric","radii":[4,4,4],"n":2}})" +
                        far_balls(ShadowBeams::kFewBlobs) +
                        R"(]}}], "lights": [{"type": "directional", )"
                        R"("direction": )" +
                        direction + "}]}",
                    "<test>");
    const std::vector<TracedObject> objects = traced_objects(scene);
    const SceneTracers tracers(objects, LipschitzMode::Local);
    const ShadowBeams beams(scene, tracers);
    ASSERT_TRUE(beams.active());
    const Box& box = scene.objects[0].bounds;
    // 10 beyond the box, where the rays come from.
    const double z = scene.lights[0].direction.z < 0 ? box.lo.z - 10 : box.hi.z + 10;
    const auto at = [&](double x, double y) { return Vec3{x, y, z}; };
    for (const double last : {-0.1, 0.1}) {
      const double m = 0.2;
      const ShadowBeams::Point points[] = {
          {at(box.hi.x + 3, 0), m}, {at(box.hi.x + 2, 1), m}, {at(box.hi.x + m + last, -1), m}};
      ShadowBeams::Lists lists;
      for (int level = 0; level < ShadowBeams::kLevels; ++level)
        beams.build(level, points, 0, 3, lists);
      const BlobBeam& list = beams.view(ShadowBeams::kLevels - 1, lists).of(0)[0];
      EXPECT_EQ(list.clear, last > 0) << direction << " " << last;
    }
  }
}

// A sum of at most ShadowBeams::kFewBlobs blobs takes no lists (its shadow rays walk it whole);
// one more, and it does, for a directional and a point light.
TEST(ShadowBeams, AFewBlobsTakeNoLists) {
  for (const char* light : {R"({"type": "directional", "direction": [0, 0, -1]})",
                            R"({"type": "point", "position": [0, 0, 30]})"})
    for (const int n : {1, ShadowBeams::kFewBlobs, ShadowBeams::kFewBlobs + 1}) {
      const Scene scene =
          parse_scene(R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)"
                      R"({"type":"soft_object","potential":{"type":"murakami"},)"
                      R"("distance":{"type":"lp_metric","radii":[4,4,4],"n":2}})" +
                          far_balls(n - 1) + R"(]}}], "lights": [)" + light + "]}",
                      "<test>");
      const std::vector<TracedObject> objects = traced_objects(scene);
      const SceneTracers tracers(objects, LipschitzMode::Local);
      ASSERT_EQ(tracers[0].blob_count(), n);
      EXPECT_EQ(ShadowBeams(scene, tracers).active(), n > ShadowBeams::kFewBlobs) << n << light;
    }
}

TEST(ShadowBeams, ANegativeBlobLeavesNoBlocker) {
  for (const char* light : {R"({"type": "directional", "direction": [0, 0, -1]})",
                            R"({"type": "point", "position": [0, 0, 30]})"})
    for (const char* strength : {"-1", "0.2"}) {
      const Scene scene = parse_scene(
          R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)"
          R"({"type":"soft_object","potential":{"type":"murakami"},)"
          R"("distance":{"type":"lp_metric","radii":[4,4,4],"n":2}},)"
          R"({"type":"soft_object","potential":{"type":"murakami"},"strength":)" +
              std::string(strength) + R"(,"distance":{"type":"lp_metric","radii":[4,4,4],"n":2}})" +
              far_balls(ShadowBeams::kFewBlobs) +
              R"(]}}],)"
              R"("lights": [)" +
              light + "]}",
          "<test>");
      const std::vector<TracedObject> objects = traced_objects(scene);
      const SceneTracers tracers(objects, LipschitzMode::Local);
      const ObjectTracer& tr = tracers[0];
      ASSERT_TRUE(tr.blob_sum());
      const ShadowBeams beams(scene, tracers);
      ASSERT_TRUE(beams.active());
      // A block's rays start below the balls, within 0.2 of the axis, and go up through them.
      const ShadowBeams::Point points[] = {{{0.1, 0, -10}, 0.05}, {{0, -0.1, -10}, 0.05}};
      ShadowBeams::Lists lists;
      for (int level = 0; level < ShadowBeams::kLevels; ++level)
        beams.build(level, points, 0, 2, lists);
      const BlobBeam& list = beams.view(ShadowBeams::kLevels - 1, lists).of(0)[0];
      ASSERT_TRUE(list.valid);
      ASSERT_EQ(list.toward, std::string(light).find("point") != std::string::npos);
      EXPECT_EQ(list.blockers.empty(), std::string(strength) == "-1") << strength << light;
      for (const ShadowBeams::Point& p : points) {
        LightArrival at;
        ASSERT_TRUE(light_arrival(scene.lights[0], p.p, p.p, at));
        const double far = std::min(at.distance, 1e3);
        const Ray ray{p.p, at.to_light, 0, 0};
        TraceCounters a, b;
        const MarchResult walk = tr.first_hit(ray, 0, far, a, Query::Any);
        const MarchResult with = tr.first_hit(ray, 0, far, b, Query::Any, 0, &list);
        EXPECT_EQ(walk.hit, std::string(strength) != "-1") << strength << light;
        EXPECT_EQ(with.hit, walk.hit) << strength << light;
        // Only a blocker decides a ray with one point and no stretch.
        EXPECT_EQ(b.box_evals == 0, !list.blockers.empty()) << strength << light;
      }
    }
}

// A shadow ray whose held list is longer than kWholeShadowList (16) entries takes its way as one
// stretch where at most 16 of the entries' ranges meet it, and in stretches where more do
// (first_hit_blobs): the count that decides it stops once it passes 16, a block of entries at a
// time, and must decide as a count of the whole list. 41 balls in a row, none of whose supports
// the ray (between two of them) meets, so each stretch is one box evaluation and no more: the
// ray's way through the box is [-1, 1] on the list's axis, and the list's entries are put on it
// or past it, the ones on it at the list's start, its end (the last one past the blocks of eight,
// where the count reads the rest one by one) or spread.
TEST(ShadowBeams, ALongListsRayGoesInOneStretchWhereAtMost16BlobsAreOnItsWay) {
  const Scene scene =
      parse_scene(R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)"
                  R"({"type":"soft_object","potential":{"type":"murakami"},"translate":[90,0,0],)"
                  R"("distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})" +
                      far_balls(40) + R"(]}}]})",
                  "<test>");
  const std::vector<TracedObject> objects = traced_objects(scene);
  const SceneTracers tracers(objects, LipschitzMode::Local);
  const ObjectTracer& tr = tracers[0];
  ASSERT_TRUE(tr.blob_sum());
  ASSERT_EQ(tr.blob_count(), 41);
  const Vec3 along{0, 0, 1};
  const Ray ray{{205, 0, -10}, along, 0, 0};
  BlobBeam list;
  list.valid = true;
  list.parallel = true;
  list.prism = ShadowPrism{{0, 0, 0}, along, {1, 0, 0}, {0, 1, 0}, 200, 210, -1, 1, -20};
  for (const int on_way : {16, 17})
    for (const int first : {0, 41 - on_way, -1}) {  // -1: every other entry from the end
      std::vector<bool> on(41, false);
      for (int k = 0; k < on_way; ++k) on[first < 0 ? 40 - 2 * k : first + k] = true;
      list.entries.clear();
      for (int id = 0; id < 41; ++id)
        list.entries.push_back(on[id] ? BlobBeam::Entry{-5, 5, id} : BlobBeam::Entry{50, 60, id});
      TraceCounters work;
      EXPECT_FALSE(tr.first_hit(ray, 0, 1e3, work, Query::Any, 0, &list).hit);
      EXPECT_EQ(work.point_evals, 0);
      if (on_way <= 16)
        EXPECT_EQ(work.box_evals, 1) << on_way << " from " << first;
      else
        EXPECT_GT(work.box_evals, 1) << on_way << " from " << first;
    }
}

// A list whose prism is wider than any ball's reach is not searched for blockers (ObjectTracer::
// blocker_reach2): that must never drop a ball the search would pick. A ball of radius 4
// (Murakami's or Wyvill's, two strengths) with a weaker one far away listed before it (whose reach
// is the smaller), under a prism centred on it: over half-sides from 0.5 to 3 in steps of 0.002,
// the ball is picked exactly where its potential at the rectangle's corner exceeds iso by 1e-3 of
// it, as shadow_blockers' own rule says (a bound 1 % too tight, or the weak ball's taken for the
// strong one's, drops some).
TEST(ShadowBeams, AListNarrowerThanABallsReachPicksItAsTheSearchDoes) {
  for (const char* potential : {"murakami", "wyvill"})
    for (const char* strength : {"1", "0.6"}) {
      const auto ball = [&](const char* at, const char* s) {
        return std::string(R"({"type":"soft_object","potential":{"type":")") + potential +
               R"("},"strength":)" + s + R"(,"translate":[)" + at +
               R"(],"distance":{"type":"lp_metric","radii":[4,4,4],"n":2}})";
      };
      const Scene scene =
          parse_scene(R"({"objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)" +
                          ball("-100,0,0", "0.52") + "," + ball("0,0,0", strength) +
                          far_balls(ShadowBeams::kFewBlobs) + R"(]}}]})",
                      "<test>");
      const std::vector<TracedObject> objects = traced_objects(scene);
      const SceneTracers tracers(objects, LipschitzMode::Local);
      const ObjectTracer& tr = tracers[0];
      ASSERT_TRUE(tr.blob_sum());
      // The rays run along `along` from 10 below the ball's centre (the origin).
      const Vec3 along = Vec3{0.3, -0.2, 1} / length(Vec3{0.3, -0.2, 1});
      Vec3 u = cross(along, Vec3{1, 0, 0});
      u = u / length(u);
      const Vec3 v = cross(along, u) / length(cross(along, u));
      int picked = 0, left = 0;
      for (int i = 0; i <= 1250; ++i) {
        const double h = 0.5 + 0.002 * i;
        const ShadowPrism prism{along * -10.0, along, u, v, -h, h, -h, h, -0.1};
        BlobBeam list;
        tr.shadow_beam(prism, nullptr, &list);
        ASSERT_TRUE(list.valid);
        ASSERT_EQ(list.entries.size(), 1u);
        tr.shadow_blockers(&list);
        // The corner at the centre's depth: the ball's potential alone (the others are far).
        const double f = tr.eval(u * h + v * h, nullptr);
        if (std::abs(f - 0.5 * (1 + 1e-3)) < 1e-9) continue;  // the rounding decides
        const bool picks = f > 0.5 * (1 + 1e-3);
        EXPECT_EQ(!list.blockers.empty(), picks) << potential << " " << strength << " " << h;
        picked += picks, left += !picks;
      }
      EXPECT_GT(picked, 100) << potential << strength;
      EXPECT_GT(left, 100) << potential << strength;
    }
}

// A shadow ray of a prism's list takes its stretches' blobs from the listed ones whose bounding
// spheres its line passes within reach of (first_hit_blobs): that may drop only blobs that give
// it no term. Every ray of every block, from its lifted point and from points across its block's
// rectangle, must get from its list what it gets from the same list without its `across` (which
// is read whole), to the bit and with the same work, as a shadow ray and as a camera-like
// (Query::Nearest) one: the same hit, the same t and every counter. Rays whose lines pass some
// listed blob's sphere by more than its reach must be common, and so must hits. It fails with the
// reach taken 0.9 times as large (blobs grazed near their supports' edges lost).
TEST(ShadowBeams, AShadowRaysStretchesTakeTheBlobsItsLinePassesAsTheWholeList) {
  std::mt19937_64 rng(23);
  for (const int cloud : {0, 1})
    for (const char* direction : {"[1, 0.35, -1]", "[-0.3, 0.2, 1]"}) {
      CloudOverFloor floor(
          cloud, std::string(R"({"type": "directional", "direction": )") + direction + "}", rng);
      const ObjectTracer& tr = floor.tracer();
      const Vec3 along = -floor.scene().lights[0].direction;
      std::uniform_real_distribution<double> u(0, 1);
      int rays = 0, passed_by = 0, hits = 0;
      floor.for_each_block(
          [&](const BlobBeam* list, const std::vector<CloudOverFloor::Lit>& block) {
            if (!list[0].valid || list[0].clear || block.empty()) return;
            ASSERT_TRUE(list[0].parallel);
            ASSERT_EQ(list[0].across.size(), list[0].entries.size());
            BlobBeam whole = list[0];
            whole.across.clear();
            const ShadowPrism& p = list[0].prism;
            for (const CloudOverFloor::Lit& l : block)
              for (int k = 0; k < 4; ++k) {
                // k > 0: from a point across the block's rectangle at the lit point's depth.
                Vec3 o = l.origin;
                if (k > 0) {
                  const Vec3 q = o - p.origin;
                  const double x = p.x0 + (p.x1 - p.x0) * u(rng), y = p.y0 + (p.y1 - p.y0) * u(rng);
                  o = p.origin + p.u * x + p.v * y + p.along * dot(q, p.along);
                }
                const Ray ray{o, along, 0, 0};
                double base, at[2];
                if (!list[0].holds(ray, &base, 1e3, &at)) continue;
                ++rays;
                for (const BlobBeam::Across& a : list[0].across) {
                  const double dx = a.x - at[0], dy = a.y - at[1];
                  if (dx * dx + dy * dy > a.reach * a.reach) {
                    ++passed_by;
                    break;
                  }
                }
                for (const Query query : {Query::Any, Query::Nearest}) {
                  TraceCounters a, b;
                  const MarchResult with = tr.first_hit(ray, 0, 1e3, a, query, 0, &list[0]);
                  const MarchResult read = tr.first_hit(ray, 0, 1e3, b, query, 0, &whole);
                  ASSERT_EQ(with.hit, read.hit) << "ray " << rays;
                  ASSERT_EQ(with.t, read.t) << "ray " << rays;
                  ASSERT_EQ(a.point_evals, b.point_evals) << "ray " << rays;
                  ASSERT_EQ(a.box_evals, b.box_evals) << "ray " << rays;
                  ASSERT_EQ(a.refine_iterations, b.refine_iterations) << "ray " << rays;
                  ASSERT_EQ(a.undecided, b.undecided) << "ray " << rays;
                  ASSERT_EQ(a.give_ups, b.give_ups) << "ray " << rays;
                  ASSERT_EQ(a.entered_box, b.entered_box) << "ray " << rays;
                  hits += with.hit && query == Query::Nearest;
                }
              }
          });
      EXPECT_GT(rays, 1000) << direction;
      EXPECT_GT(passed_by, rays / 2) << direction;
      EXPECT_GT(hits, rays / 30) << direction;
    }
}

// Two lists the same: every member a shadow ray or a list built from it may read.
void expect_same_list(const BlobBeam& a, const BlobBeam& b, int block) {
  ASSERT_EQ(a.valid, b.valid) << "block " << block;
  ASSERT_EQ(a.clear, b.clear) << "block " << block;
  ASSERT_EQ(a.shut, b.shut) << "block " << block;
  if (!a.valid && !a.shut) return;  // no list: its members are what the last build left
  ASSERT_EQ(a.parallel, b.parallel) << "block " << block;
  ASSERT_EQ(a.toward, b.toward) << "block " << block;
  const ShadowPrism &p = a.prism, &q = b.prism;
  ASSERT_TRUE(p.x0 == q.x0 && p.x1 == q.x1 && p.y0 == q.y0 && p.y1 == q.y1 && p.z0 == q.z0 &&
              p.z1 == q.z1 && p.origin.x == q.origin.x && p.origin.y == q.origin.y &&
              p.origin.z == q.origin.z)
      << "block " << block;
  ASSERT_EQ(a.entries.size(), b.entries.size()) << "block " << block;
  for (size_t i = 0; i < a.entries.size(); ++i)
    ASSERT_TRUE(a.entries[i].near == b.entries[i].near && a.entries[i].far == b.entries[i].far &&
                a.entries[i].id == b.entries[i].id)
        << "block " << block << " entry " << i;
  ASSERT_EQ(a.across.size(), b.across.size()) << "block " << block;
  for (size_t i = 0; i < a.across.size(); ++i)
    ASSERT_TRUE(a.across[i].x == b.across[i].x && a.across[i].y == b.across[i].y &&
                a.across[i].reach == b.across[i].reach && a.across[i].depth == b.across[i].depth)
        << "block " << block << " entry " << i;
  ASSERT_EQ(a.blockers, b.blockers) << "block " << block;
  // Read only with blockers, and with a shut list (shadow_blockers leaves them otherwise).
  if (!a.blockers.empty()) {
    ASSERT_EQ(a.blockers_err, b.blockers_err) << "block " << block;
  }
  if (a.shut) {
    ASSERT_EQ(a.shut_footprint, b.shut_footprint) << "block " << block;
  }
}

// The frame builds a block's lists when its first shadow ray asks for them (ShadowListsOnDemand:
// a block whose points all face away from the lights casts none), and the tile's and its
// quarter's with them. Whichever blocks ask, and whichever quarters have no block that asks, each
// block that does gets the lists the tile-quarter-blocks order builds, member by member, for a
// directional and a point light together: over the mixed cloud, and over the positive balls
// finer, whose tiles and quarters lend their shut lists to their blocks (Lists::lent: the state a
// skipped quarter or block must not leave wrong).
TEST(ShadowBeams, ABlocksListsBuiltOnDemandAreTheOnesBuiltInOrder) {
  std::mt19937_64 rng(41);
  int asked = 0, skipped = 0, shut = 0, clear = 0, toward = 0;
  for (const int cloud : {0, 1}) {
    CloudOverFloor floor(cloud,
                         R"({"type": "directional", "direction": [1, 0.35, -1]},
                            {"type": "point", "position": [30, -20, 60]})",
                         rng, cloud == 1 ? 3 : 1);
    const ShadowBeams& beams = floor.beams();
    ShadowBeams::Lists in_order, on_demand_lists;
    std::bernoulli_distribution asks(0.5), quarter_asks(0.7);
    floor.for_each_tile([&](const std::vector<ShadowBeams::Point>& points, const int(&start)[17],
                            const std::vector<CloudOverFloor::Lit>(&)[16]) {
      ShadowListsOnDemand on_demand(beams, points.data(), start, on_demand_lists);
      beams.build(0, points.data(), 0, start[16], in_order);
      for (int q = 0; q < 4; ++q) {
        beams.build(1, points.data(), start[q * 4], start[q * 4 + 4], in_order);
        const bool quarter = quarter_asks(rng);
        for (int b = q * 4; b < q * 4 + 4; ++b) {
          beams.build(2, points.data(), start[b], start[b + 1], in_order);
          const ShadowLists want = beams.view(2, in_order);
          on_demand.block(b);
          if (!quarter || !asks(rng)) {
            ++skipped;
            continue;
          }
          ++asked;
          for (int light = 0; light < 2; ++light)
            for (int o = 0; o < want.objects; ++o) {
              const BlobBeam& a = want.of(light)[o];
              expect_same_list(a, on_demand.of(light)[o], b);
              if (::testing::Test::HasFatalFailure()) return;
              shut += a.shut, clear += a.clear, toward += a.valid && a.toward;
            }
        }
      }
    });
    ASSERT_FALSE(::testing::Test::HasFatalFailure());
  }
  std::printf("blocks asked: %d, not asked: %d; lists shut: %d, clear: %d, towards: %d\n", asked,
              skipped, shut, clear, toward);
  EXPECT_GT(asked, 1000);
  EXPECT_GT(shut, 100);
  EXPECT_GT(clear, 100);
  EXPECT_GT(toward, 100);
}

// The frame traces a whole tile's camera rays before it shades any (the shadow lists need their
// hits), and a hit's normal takes the blob list of the 4-pixel beam that traced it
// (TraceHit::blobs): the next beam of the tile overwrites that list before shading unless the
// frame keeps it. Every pixel's normal must be the point query's at its hit.
TEST(FrameNormals, EveryPixelsNormalIsThePointQuerysAtItsHit) {
  std::mt19937_64 rng(5);
  const std::string text =
      R"({"camera":{"eye":[60,-80,50],"target":[0,0,0],"up":[0,0,1],"fov":50},)"
      R"("objects":[{"iso":0.5,"field":{"type":"soft_blend","children":[)" +
      mixed_blob_cloud(rng) + "]}}]}";
  const std::string dir = test::temp_dir("frame_normals");
  { std::ofstream(dir + "/cloud.json") << text; }
  constexpr int kW = 96, kH = 64;
  const test::RunResult r = test::run_softtrace(
      "render " + dir + "/cloud.json -q --width " + std::to_string(kW) + " --height " +
      std::to_string(kH) + " --aov depth,normal -o " + dir + "/n.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  const ImageFile img = read_image(dir + "/n.exr");
  const int z = img.channel("Z"), nx = img.channel("N.X"), ny = img.channel("N.Y"),
            nz = img.channel("N.Z");
  ASSERT_TRUE(z >= 0 && nx >= 0 && ny >= 0 && nz >= 0);
  const Scene scene = parse_scene(text, "<test>");
  const ObjectTracer tr(trace_target(scene.objects[0]), LipschitzMode::Local);
  ASSERT_TRUE(tr.blob_sum());
  const ViewCamera camera(scene.camera, kW, kH);
  int hits = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float t = img.at(x, y, z);
      if (!std::isfinite(t)) continue;
      ++hits;
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      // Z is stored as a float: the point is off the hit by ~1e-7 of its distance, which moves
      // the normal far less than the tolerance; a wrong list's normal is off by ~1.
      Vec3 n = tr.normal(ray.o + ray.d * double(t));
      if (dot(n, ray.d) > 0) n = n * -1.0;
      ASSERT_NEAR(img.at(x, y, nx), n.x, 1e-3) << "pixel " << x << "," << y;
      ASSERT_NEAR(img.at(x, y, ny), n.y, 1e-3) << "pixel " << x << "," << y;
      ASSERT_NEAR(img.at(x, y, nz), n.z, 1e-3) << "pixel " << x << "," << y;
    }
  EXPECT_GT(hits, kW * kH / 10);
}

}  // namespace
}  // namespace softtrace

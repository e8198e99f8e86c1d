// Background beams (render/beam_misses.h): a beam whose frustum misses every object's box with a
// margin no rounding can eat has its pixels written as misses without a ray each (frame.cpp). So
// every camera ray of a certified beam, wherever in its pixel it starts, must be clipped away by
// every object's box (clip_to_box, as the tracers clip it) and get intersect()'s answer of no hit
// and no work; a box past a side plane by less than the margin is not certified; and the frame's
// counters are those of its rays traced one by one.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include <vector>

#include "render/beam_misses.h"
#include "render/camera.h"
#include "render/frame.h"
#include "scene/scene.h"
#include "sparse_ball_cloud.h"

namespace softtrace {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// `n` balls at random, seen through `camera` (sparse_ball_cloud.h).
std::string background_cloud(int n, const std::string& camera) {
  return sparse_ball_cloud(n, 30, camera);
}

// Fields of both kinds, a CSG and primitives apart from one another (Embree's path; each box
// certified on its own): a blob cloud, a capsule (no blob sum: its beams count their work), a
// merge of a box and a ball, a ball and a box.
std::string background_mixed(const std::string& camera) {
  std::string scene = background_cloud(40, camera);
  const std::string others = R"(,
    {"convention": "constructive",
     "field": {"type": "segment", "p0": [27, 0, 0], "p1": [33, 0, 0], "radius": 1.5}},
    {"csg": "merge", "operands": [
      {"shape": {"type": "box", "corner1": [-34, -3, -3], "corner2": [-28, 3, 3]}},
      {"shape": {"type": "sphere", "center": [-31, 0, 4], "radius": 3}}]},
    {"shape": {"type": "sphere", "center": [0, 0, 31], "radius": 4}},
    {"shape": {"type": "box", "corner1": [-3, 22, -24], "corner2": [3, 28, -18]}}]})";
  scene.replace(scene.size() - 2, 2, others);
  return scene;
}

// Views: the objects in the middle, at the frame's edges and corners (their outlines across
// beams of every level), and turned away from all of them.
const std::vector<std::string>& views() {
  static const std::vector<std::string> all = {
      R"({"eye": [70, -95, 60], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 45})",
      R"({"eye": [70, -95, 60], "target": [-25, 10, 21], "up": [0, 0, 1], "fov": 40})",
      R"({"eye": [70, -95, 60], "target": [33, 13, -17], "up": [0, 0, 1], "fov": 23})",
      R"({"eye": [3, -60, 2], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 80})",
      R"({"eye": [70, -95, 60], "target": [140, -190, 120], "up": [0, 0, 1], "fov": 60})",
  };
  return all;
}

// Every object's boxes: its own and its field's (where its tracer clips).
std::vector<Box> object_boxes(const TracedScene& rt) {
  std::vector<Box> boxes;
  for (const TracedObject& o : rt.objects) {
    boxes.push_back(o.bounds);
    if (o.field) boxes.push_back(o.field->bounds);
  }
  return boxes;
}

struct BeamWalk {
  int beams = 0, certified = 0;
  int edge = 0;  // certified 4-pixel beams beside one that is not
  // Certified beams that meet the rectangle around the boxes' corners on screen (the box's
  // outline certifies them: BeamMisses::Outline).
  int inside = 0;
  long rays = 0;
};

// Every beam of a kW x kH frame as frame.cpp nests them (tiles of 16, their quarters and theirs),
// each asked on its own; every ray of a certified one (its pixels' centres and corners and a
// random point in each) must miss every box and get no hit and no work from intersect().
void walk_beams(const Scene& scene, const TracedScene& rt, BeamWalk& walk) {
  constexpr int kW = 128, kH = 96;
  const ViewCamera camera(scene.camera, kW, kH);
  ASSERT_TRUE(camera.single_eye());
  const BeamMisses misses(rt.tracers, camera);
  const std::vector<Box> boxes = object_boxes(rt);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  // The 4-pixel beams' answers, to find certified ones beside others.
  std::vector<char> leaf(size_t(kW / 4) * (kH / 4), 0);
  double rx0 = kFar, ry0 = kFar, rx1 = -kFar, ry1 = -kFar;
  for (const Box& box : boxes)
    for (int c = 0; c < 8; ++c) {
      double px, py;
      if (!camera.pixel_of(box.corner(c), px, py)) continue;
      rx0 = std::min(rx0, px), ry0 = std::min(ry0, py);
      rx1 = std::max(rx1, px), ry1 = std::max(ry1, py);
    }
  for (int size = 16; size >= 4; size /= 2)
    for (int y = 0; y < kH; y += size)
      for (int x = 0; x < kW; x += size) {
        ++walk.beams;
        const Frustum fr = camera.frustum(x, y, x + size, y + size);
        if (!misses.misses(fr, x, y, x + size, y + size)) continue;
        ++walk.certified;
        walk.inside += x < rx1 && rx0 < x + size && y < ry1 && ry0 < y + size;
        if (size == 4) leaf[size_t(y / 4) * (kW / 4) + x / 4] = 1;
        for (int py = y; py < y + size; ++py)
          for (int px = x; px < x + size; ++px) {
            // The extremes a sample may take (its offset in [0, 1)) and points inside.
            const double at[6][2] = {
                {0.5, 0.5},      {0, 0}, {0.9999999, 0}, {0, 0.9999999}, {0.9999999, 0.9999999},
                {u(rng), u(rng)}};
            for (const auto& d : at) {
              const Ray ray = camera.generate(px + d[0], py + d[1]);
              ++walk.rays;
              for (const Box& box : boxes) {
                double t0 = 0, t1 = kFar;
                ASSERT_FALSE(clip_to_box(ray, box, t0, t1))
                    << "pixel (" << px << ", " << py << ") of a certified " << size
                    << "-pixel beam enters a box at " << t0;
              }
              const TraceHit hit = rt.embree.intersect(ray, 0, kFar);
              ASSERT_FALSE(hit.hit) << "pixel (" << px << ", " << py << ")";
              ASSERT_EQ(hit.work.evaluations(), 0);
              ASSERT_FALSE(hit.work.entered_box);
            }
          }
      }
  for (int y = 0; y < kH / 4; ++y)
    for (int x = 0; x < kW / 4; ++x) {
      if (!leaf[size_t(y) * (kW / 4) + x]) continue;
      bool beside = false;
      for (int k = 0; k < 4; ++k) {
        const int nx = x + (k == 0) - (k == 1), ny = y + (k == 2) - (k == 3);
        if (nx >= 0 && ny >= 0 && nx < kW / 4 && ny < kH / 4 && !leaf[size_t(ny) * (kW / 4) + nx])
          beside = true;
      }
      walk.edge += beside;
    }
}

TEST(BackgroundBeams, CertifiedBeamsRaysMissEveryBox) {
  for (size_t v = 0; v < views().size(); ++v) {
    SCOPED_TRACE("view " + std::to_string(v));
    for (const bool mixed : {false, true}) {
      SCOPED_TRACE(mixed ? "mixed scene" : "cloud");
      const Scene scene = parse_scene(
          mixed ? background_mixed(views()[v]) : background_cloud(300, views()[v]), "<test>");
      const TracedScene rt(scene, LipschitzMode::Local);
      ASSERT_EQ(rt.embree.built(), mixed);  // the direct path of a lone field, or Embree's
      BeamWalk walk;
      walk_beams(scene, rt, walk);
      if (HasFatalFailure()) return;
      if (v + 1 == views().size()) {  // turned away: every beam
        EXPECT_EQ(walk.certified, walk.beams);
        continue;
      }
      // Not vacuous: the objects are seen, much of the frame is background, and it is certified up
      // to the objects' outlines (a 4-pixel beam beside one that is not).
      EXPECT_LT(walk.certified, walk.beams * 9 / 10);
      EXPECT_GT(walk.certified, walk.beams / 10);
      EXPECT_GT(walk.edge, 8);
      // The lone cloud's box is seen as a hexagon but from view 3 (nearly face on: a rectangle).
      if (!mixed && v != 3) {
        EXPECT_GT(walk.inside, 8);
      }
    }
  }
}

// A box just past a side plane: certified only with the margin between (1e-5 of the
// coordinates); one the beam's edge ray meets, or within the margin of it, is not.
TEST(BackgroundBeams, MarginNoRoundingCanEat) {
  // Rays from the origin with forward component 1 and x/z, y/z in [-0.1, 0.1].
  const Frustum f{
      {0, 0, 0}, {0, 0, 1}, {{-0.1, -0.1, 1}, {0.1, -0.1, 1}, {-0.1, 0.1, 1}, {0.1, 0.1, 1}}};
  // At z = 11 (the box's far face) the beam reaches x = 1.1.
  const auto box = [](double lo) { return Box({lo, -1, 9}, {lo + 1, 1, 11}); };
  EXPECT_TRUE(BeamMisses::misses_box(f, box(1.2)));
  EXPECT_TRUE(BeamMisses::misses_box(f, box(1.101)));
  EXPECT_FALSE(BeamMisses::misses_box(f, box(1.1 + 1e-9)));  // within the margin
  EXPECT_FALSE(BeamMisses::misses_box(f, box(1.1)));         // the edge ray touches it
  EXPECT_FALSE(BeamMisses::misses_box(f, box(1.0)));         // the beam enters it
  // Behind the eye, and across the eye's plane.
  EXPECT_TRUE(BeamMisses::misses_box(f, Box({-1, -1, -3}, {1, 1, -1})));
  EXPECT_FALSE(BeamMisses::misses_box(f, Box({-1, -1, -3}, {1, 1, -1e-9})));
  EXPECT_FALSE(BeamMisses::misses_box(f, Box({-1, -1, -3}, {1, 1, 1})));
  // A box holding the eye.
  EXPECT_FALSE(BeamMisses::misses_box(f, Box({-1, -1, -1}, {1, 1, 1})));
}

// The box's outline (BeamMisses::Outline): a cube seen along its diagonal is a hexagon, whose
// bounding rectangle's corners it does not cover. A narrow beam past one of its sides by twice
// the side's margin is certified and its rays miss the box; one within the margin, or one that
// meets the box, is not.
TEST(BackgroundBeams, OutlineCertifiesBeamsBesideTheHexagon) {
  const Box box({-1, -1, -1}, {1, 1, 1});
  const Vec3 eye{10, 9, 11};
  const BeamMisses::Outline outline = BeamMisses::outline_of(eye, box);
  ASSERT_EQ(outline.sides, 6);
  const Vec3 centre = box.center() - eye;
  // A beam of rays within `w` (radians, about) of direction d.
  const auto beam = [&](const Vec3& d, double w) {
    const Vec3 f = normalize(d);
    const Vec3 a = normalize(cross(f, Vec3{0, 0, 1})), b = cross(a, f);
    Frustum fr{eye, f, {}};
    for (int k = 0; k < 4; ++k)
      fr.corner[k] = (f + a * ((k & 1) ? w : -w) + b * ((k & 2) ? w : -w));
    return fr;
  };
  int certified = 0;
  for (int s = 0; s < outline.sides; ++s) {
    SCOPED_TRACE("side " + std::to_string(s));
    const BeamMisses::Outline::Side& side = outline.side[s];
    const Vec3 n = normalize(side.n);
    // From the centre's direction to the side's plane, then past it by `by`.
    const Vec3 c = normalize(centre);
    const auto past = [&](double by) { return c - n * (dot(c, n) + by); };
    const double limit = side.limit / length(side.n);
    EXPECT_GT(limit, 0);
    EXPECT_LT(limit, 1e-6);
    const Frustum out = beam(past(0.01), 1e-3);
    EXPECT_TRUE(BeamMisses::beyond(outline, out));
    for (int k = 0; k < 4; ++k) {
      double t0 = 0, t1 = kFar;
      EXPECT_FALSE(clip_to_box(Ray{eye, normalize(out.corner[k])}, box, t0, t1));
    }
    certified += BeamMisses::beyond(outline, beam(past(3 * limit), 0));
    EXPECT_FALSE(BeamMisses::beyond(outline, beam(past(0.5 * limit), 0)));
    EXPECT_FALSE(BeamMisses::beyond(outline, beam(past(-0.01), 1e-3)));  // meets the box
  }
  EXPECT_EQ(certified, outline.sides);
  EXPECT_FALSE(BeamMisses::beyond(outline, beam(centre, 0.05)));
  // An eye inside the box, or by it within the padding: no outline.
  EXPECT_EQ(BeamMisses::outline_of({0.5, 0, 0}, box).sides, 0);
  EXPECT_EQ(BeamMisses::outline_of({1 + 1e-9, 0, 0}, box).sides, 0);
}

// The outline holds for rays from the eye it was made for, which every beam of a pinhole camera
// leaves; an orthographic camera's rays and a lens's leave other points, and their frames make no
// beams: BeamMisses certifies nothing for them (ever() false, misses() false for any beam), where
// the same view through a pinhole certifies beams.
TEST(BackgroundBeams, NoBeamOfACameraWithoutOneEyeIsCertified) {
  constexpr int kW = 128, kH = 96;
  const std::string view = R"({"eye": [70, -95, 60], "target": [0, 0, 0], "up": [0, 0, 1], )";
  const Scene pinhole_scene = parse_scene(background_cloud(40, view + R"("fov": 45})"), "<test>");
  const ViewCamera pinhole(pinhole_scene.camera, kW, kH);
  for (const char* lens :
       {"", R"(, "projection": "orthographic")", R"(, "aperture": 2, "focal_distance": 130)"}) {
    SCOPED_TRACE(lens);
    const Scene scene =
        parse_scene(background_cloud(40, view + R"("fov": 45)" + lens + "}"), "<test>");
    const TracedScene rt(scene, LipschitzMode::Local);
    const ViewCamera camera(scene.camera, kW, kH);
    const BeamMisses misses(rt.tracers, camera);
    EXPECT_EQ(misses.ever(), camera.single_eye());
    // The pinhole's tiles' beams, asked of each.
    int certified = 0;
    for (int y = 0; y < kH; y += 16)
      for (int x = 0; x < kW; x += 16)
        certified += misses.misses(pinhole.frustum(x, y, x + 16, y + 16), x, y, x + 16, y + 16);
    if (camera.single_eye())
      EXPECT_GT(certified, 4);
    else
      EXPECT_EQ(certified, 0);
  }
}

// The frame's counters and AOVs: its background pixels' rays counted as rays that met nothing,
// and the rays that enter the cloud's box (the pixels' centres, one sample each) exactly those the
// tracer's own clip lets in.
TEST(BackgroundBeams, FrameCountersAreTheRaysOwn) {
  for (size_t v = 0; v < views().size(); ++v) {
    SCOPED_TRACE("view " + std::to_string(v));
    const Scene scene = parse_scene(background_cloud(300, views()[v]), "<test>");
    const TracedScene rt(scene, LipschitzMode::Local);
    constexpr int kW = 128, kH = 96;
    const ViewCamera camera(scene.camera, kW, kH);
    Film film(kW, kH);
    FrameStats stats;
    ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, film, nullptr, &stats));
    EXPECT_EQ(stats.primary.rays, kW * kH);
    long entered = 0, misses = 0;
    const Box& box = rt.objects[0].field->bounds;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const Ray ray = camera.generate(x + 0.5, y + 0.5);
        double t0 = 0, t1 = kFar;
        if (clip_to_box(ray, box, t0, t1)) {
          ++entered;
          continue;
        }
        ++misses;
        const size_t i = size_t(y) * kW + x;
        ASSERT_EQ(film.depth[i], std::numeric_limits<float>::infinity());
        ASSERT_EQ(film.steps[i], 0.0f);
        for (int k = 0; k < 4; ++k) ASSERT_EQ(film.rgba[i * 4 + k], 0.0f);
      }
    EXPECT_EQ(stats.primary.entered_box, entered);
    EXPECT_GT(misses, kW * kH / 10);
    if (v + 1 == views().size()) {
      EXPECT_EQ(entered, 0);
      EXPECT_EQ(stats.primary.evaluations(), 0);
    }
  }
}

}  // namespace
}  // namespace softtrace

// The tracer never skips a surface: its first hit agrees with a dense-sampling reference march,
// for local and global Lipschitz bounds, on smooth fields and on fields with exponents below 1
// (no global bound: intervals and subdivision must carry it), including grazing rays.
#include <gtest/gtest.h>

#include <random>

#include "scene/traced_objects.h"
#include "tracer_scenes.h"

namespace softtrace {
namespace {

using namespace tracer_scenes;

class TracerVsReference : public testing::TestWithParam<std::tuple<int, LipschitzMode>> {};

TEST_P(TracerVsReference, NeverSkipsASurface) {
  const Scene scene = parse_scene(kScenes[std::get<0>(GetParam())], "<test>");
  const SceneObject& obj = scene.objects[0];
  const ObjectTracer tr(trace_target(obj), std::get<1>(GetParam()));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const Box& b = obj.bounds;
  const double R = b.diagonal();
  int hits = 0, grazing = 0, gave_up = 0;
  Workspace ws;
  ws.fit(tr.program());
  for (int i = 0; i < 400; ++i) {
    // Rays from a sphere around the box towards random points inside it; every fourth one is
    // aimed at a surface point found by the reference and offset sideways so it grazes.
    const Vec3 dir0 = normalize({u(rng), u(rng), u(rng)});
    const Vec3 target =
        b.center() +
        Vec3{u(rng) * b.extent().x, u(rng) * b.extent().y, u(rng) * b.extent().z} * 0.4;
    Ray ray{target - dir0 * R, dir0};
    double t0 = 0, t1 = 2 * R;
    ASSERT_TRUE(clip_to_box(ray, b, t0, t1));
    double ref = reference_first_hit(tr, ray, t0, t1, 20000);
    if (i % 4 == 0 && std::isfinite(ref)) {
      const Vec3 p = ray.o + ray.d * ref, n = tr.normal(p);
      Vec3 side = cross(n, ray.d);
      if (length(side) > 1e-6) {
        ray = {p + normalize(cross(side, n)) * -R, normalize(cross(side, n))};  // along the tangent
        t0 = 0, t1 = 3 * R;
        if (!clip_to_box(ray, b, t0, t1)) continue;
        ref = reference_first_hit(tr, ray, t0, t1, 20000);
        ++grazing;
      }
    }
    const double ds = (t1 - t0) / 20000;
    TraceCounters work;
    const MarchResult m = tr.first_hit(ray, 0, 3 * R, work);
    if (std::isfinite(ref)) {
      ++hits;
      ASSERT_TRUE(m.hit) << "ray " << i << " skipped a surface at t = " << ref;
      // The tracer may find a thin crossing the samples stepped over, but never a later one.
      // Refinement stops within 1e-3 of the footprint: 1e-8 of the diagonal for rays without one.
      ASSERT_LE(m.t, ref + 2e-8 * R) << "ray " << i;
    }
    if (m.gave_up) {
      // No certificate either way: the surface may pass within a tolerance (here 1e-5 of the
      // diagonal: these rays carry no pixel footprint) of the ray there, as a flat face the ray
      // runs along. The field's bounds around that point must allow the surface.
      ++gave_up;
      const BoxBounds bb = bounds(tr.program(), Box::around(ray.o + ray.d * m.t, 1e-5 * R), ws);
      ASSERT_TRUE(bb.value.contains(obj.iso)) << "ray " << i << " gave up far from any surface";
    } else if (m.hit) {
      ASSERT_TRUE(tr.inside(ray.o + ray.d * m.t)) << "ray " << i << ": reported hit is outside";
      if (std::isfinite(ref)) {
        ASSERT_GE(m.t, ref - ds - 1e-9 * R) << "hit before the reference's sample";
      }
    }
  }
  EXPECT_GT(hits, 40);
  EXPECT_GT(grazing, 10);
  // Only rays laid along a tangent plane may end undecided, and not most of them.
  EXPECT_LE(gave_up, grazing / 2);
}

INSTANTIATE_TEST_SUITE_P(Scenes, TracerVsReference,
                         testing::Combine(testing::Range(0, kCount),
                                          testing::Values(LipschitzMode::Local,
                                                          LipschitzMode::Global)));

// The local mode traces a sum of polynomial blobs on its polynomials: no point evaluation, and
// the same hits as the segment tracer of the global mode, to the tolerance (1e-8 of the
// diagonal for these rays without a footprint, 1e-3 of that for the refinement).
TEST(BlobTracer, TracesPolynomialsAndAgreesWithTheSegmentTracer) {
  const Scene scene = parse_scene(kScenes[kBlobs], "<test>");
  const SceneObject& obj = scene.objects[0];
  const ObjectTracer blobs(trace_target(obj), LipschitzMode::Local),
      segments(trace_target(obj), LipschitzMode::Global);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const double R = obj.bounds.diagonal();
  int hits = 0, certified = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 d = normalize({u(rng), u(rng), u(rng)});
    const Vec3 target = obj.bounds.center() + Vec3{u(rng), u(rng), u(rng)} * 6;
    const Ray ray{target - d * R, d};
    TraceCounters a, b, any;
    const MarchResult m = blobs.first_hit(ray, 0, 2 * R, a);
    const MarchResult g = segments.first_hit(ray, 0, 2 * R, b);
    EXPECT_EQ(a.point_evals, 0);
    ASSERT_EQ(m.hit, g.hit) << "ray " << i;
    const MarchResult y = blobs.first_hit(ray, 0, 2 * R, any, Query::Any);
    EXPECT_EQ(y.hit, m.hit) << "ray " << i;
    // A shadow ray may end on a point the blobs' sum certainly holds (one point evaluation).
    if (any.point_evals > 0) {
      ++certified;
      EXPECT_TRUE(y.hit && blobs.inside(ray.o + ray.d * y.t)) << "ray " << i;
    }
    if (!m.hit) continue;
    ++hits;
    EXPECT_FALSE(m.gave_up);
    EXPECT_NEAR(m.t, g.t, 2e-8 * R) << "ray " << i;
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(certified, 50);
}

// A shadow ray starts at a lit point lifted off the surface: outside the solid, where the sum is
// below iso, so surely_inside is not tried at its very start (tracer_blobs.cpp); one that starts
// inside after all is found by its first piece. From points just outside and just inside the
// surface (a camera hit moved back and on along its ray), in random directions, the shadow
// question's answer must be the nearest hit's, and every ray from inside is blocked.
TEST(BlobTracer, AShadowRayFromBesideTheSurfaceAnswersAsItsNearestHit) {
  const Scene scene = parse_scene(kScenes[kBlobs], "<test>");
  const SceneObject& obj = scene.objects[0];
  const ObjectTracer blobs(trace_target(obj), LipschitzMode::Local);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const double R = obj.bounds.diagonal();
  int inside = 0, outside = 0, open = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 d = normalize({u(rng), u(rng), u(rng)});
    const Vec3 target = obj.bounds.center() + Vec3{u(rng), u(rng), u(rng)} * 6;
    const Ray ray{target - d * R, d};
    TraceCounters w;
    const MarchResult m = blobs.first_hit(ray, 0, 2 * R, w);
    if (!m.hit || m.gave_up) continue;
    for (const double lift : {-1e-4 * R, 1e-4 * R}) {
      const Vec3 o = ray.o + ray.d * (m.t + lift);
      const bool in = blobs.inside(o);
      // Back along the ray the point is outside; on past the hit, inside where the solid is
      // thicker than the lift.
      if (lift < 0) {
        ASSERT_FALSE(in) << "ray " << i;
      }
      for (int k = 0; k < 8; ++k) {
        const Ray shadow{o, normalize({u(rng), u(rng), u(rng)})};
        TraceCounters a, b;
        const MarchResult any = blobs.first_hit(shadow, 0, 2 * R, a, Query::Any);
        const MarchResult near = blobs.first_hit(shadow, 0, 2 * R, b);
        ASSERT_EQ(any.hit, near.hit) << "ray " << i << " lift " << lift << " k " << k;
        if (in) {
          ASSERT_TRUE(any.hit) << "ray " << i << " k " << k;
        }
        inside += in;
        outside += !in;
        open += !any.hit;
      }
    }
  }
  EXPECT_GT(inside, 400);
  EXPECT_GT(outside, 800);
  EXPECT_GT(open, 200);
}

// Capsules on the polynomial path: a chain of them, one of negative strength cutting a sphere, a
// zero-length one and a sheared one. Along random rays, rays grazing the surface (along a tangent
// at a reference hit) and rays along the chain's axes, the local mode's first hit is the segment
// tracer's, no later than the dense reference march's, with no point evaluation.
TEST(BlobTracer, CapsulesAgreeWithTheSegmentTracerAndTheReference) {
  const Scene scene = parse_scene(
      R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"segment","p0":[-9,0,0],"p1":[-3,1,0],"radius":2.5}},
        {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"segment","p0":[-3,1,0],"p1":[3,1,0],"radius":2.5}},
        {"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"segment","p0":[3,1,0],"p1":[6,-3,2],"radius":2.5}},
        {"type":"soft_object","potential":{"type":"murakami"},"translate":[0,-6,0],"distance":{"type":"lp_metric","radii":[5,5,5],"n":2}},
        {"type":"soft_object","potential":{"type":"murakami"},"strength":-1.2,"distance":{"type":"segment","p0":[0,-6,-7],"p1":[0,-6,7],"radius":2}},
        {"type":"soft_object","potential":{"type":"cubic"},"strength":1.6,"distance":{"type":"segment","p0":[-6,-8,4],"p1":[-6,-8,4],"radius":3}},
        {"type":"soft_object","potential":{"type":"murakami"},"matrix":[[1,0.9,0,0],[0,0.15,0,4],[0.3,0,1,-4]],
         "distance":{"type":"segment","p0":[-3,0,0],"p1":[3,0,0],"radius":1.5}}]}}]})",
      "<test>");
  const SceneObject& obj = scene.objects[0];
  const ObjectTracer blobs(trace_target(obj), LipschitzMode::Local),
      segments(trace_target(obj), LipschitzMode::Global);
  ASSERT_TRUE(blobs.blob_sum()) << "capsules should take the polynomial path";
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  const Box& b = obj.bounds;
  const double R = b.diagonal();
  int hits = 0, grazing = 0, certified = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3 dir0 = normalize({u(rng), u(rng), u(rng)});
    Vec3 target = b.center() +
                  Vec3{u(rng) * b.extent().x, u(rng) * b.extent().y, u(rng) * b.extent().z} * 0.4;
    Vec3 dir = dir0;
    // Every tenth along a capsule of the chain (the middle one's axis is the x axis at y = 1),
    // offset from the axis by up to the surface's radius.
    if (i % 10 == 5) target = Vec3{0, 1, 0} + Vec3{0, u(rng), u(rng)} * 1.6, dir = {1, 0, 0};
    if (i % 10 == 7) target = Vec3{0, -6, 0} + Vec3{u(rng), u(rng), 0} * 1.2, dir = {0, 0, 1};
    Ray ray{target - dir * R, dir};
    double t0 = 0, t1 = 2 * R;
    if (!clip_to_box(ray, b, t0, t1)) continue;
    double ref = reference_first_hit(segments, ray, t0, t1, 20000);
    if (i % 4 == 0 && std::isfinite(ref)) {
      const Vec3 p = ray.o + ray.d * ref, n = segments.normal(p);
      const Vec3 side = cross(n, ray.d);
      if (length(side) > 1e-6) {
        const Vec3 along = normalize(cross(side, n));
        ray = {p - along * R, along};
        t0 = 0, t1 = 3 * R;
        if (!clip_to_box(ray, b, t0, t1)) continue;
        ref = reference_first_hit(segments, ray, t0, t1, 20000);
        ++grazing;
      }
    }
    const double ds = (t1 - t0) / 20000;
    TraceCounters a, g;
    const MarchResult m = blobs.first_hit(ray, 0, 3 * R, a);
    const MarchResult s = segments.first_hit(ray, 0, 3 * R, g);
    EXPECT_EQ(a.point_evals, 0);
    if (std::isfinite(ref)) {
      ++hits;
      ASSERT_TRUE(m.hit) << "ray " << i << " skipped a surface at t = " << ref;
      ASSERT_LE(m.t, ref + 2e-8 * R) << "ray " << i;
    }
    if (m.gave_up || s.gave_up) continue;  // a tangency neither can certify (grazing rays)
    ASSERT_EQ(m.hit, s.hit) << "ray " << i;
    // The shadow ray's question (a negative capsule among them: a point's sum, not one blob's).
    TraceCounters any;
    const MarchResult y = blobs.first_hit(ray, 0, 3 * R, any, Query::Any);
    ASSERT_EQ(y.hit, m.hit) << "ray " << i;
    if (any.point_evals > 0) {
      ++certified;
      ASSERT_TRUE(blobs.inside(ray.o + ray.d * y.t)) << "ray " << i;
    }
    if (!m.hit) continue;
    ASSERT_TRUE(blobs.inside(ray.o + ray.d * m.t)) << "ray " << i << ": reported hit is outside";
    if (std::isfinite(ref)) {
      ASSERT_GE(m.t, ref - ds - 1e-9 * R) << "ray " << i;
    }
    ASSERT_NEAR(m.t, s.t, 2e-8 * R) << "ray " << i;
  }
  EXPECT_GT(hits, 150);
  EXPECT_GT(grazing, 20);
  EXPECT_GT(certified, 50);
}

// A solid cut by its object's bounds shows the cut as a flat face: the hit is flagged so
// shading uses the face's normal (the gradient there belongs to the uncut field, and a shadow
// ray leaving along it would start inside the solid).
TEST(BoxCut, HitsOnTheCutFaceAreFlaggedWithTheFaceNormal) {
  const Scene scene = parse_scene(
      R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"bounds":[[-5,-5,-5],[5,5,0]],
          "field":{"type":"soft_object","distance":{"type":"lp_metric","radii":[8,8,8],"n":2}}}]})",
      "<test>");
  const ObjectTracer tr(trace_target(scene.objects[0]), LipschitzMode::Local);
  TraceCounters work;
  // Straight down onto the cut at z = 0, inside the ball's d <= 0.5 (radius 4).
  const MarchResult cut = tr.first_hit({{1, 1, 10}, {0, 0, -1}}, 0, 100, work);
  ASSERT_TRUE(cut.hit);
  EXPECT_TRUE(cut.on_box_face);
  EXPECT_NEAR(cut.t, 10, 1e-9);
  const Vec3 n = tr.box_face_normal({1, 1, 0});
  EXPECT_EQ(n.z, 1);
  EXPECT_EQ(n.x, 0);
  // From the side, below the cut: the ball's own surface, not a face.
  const MarchResult side = tr.first_hit({{-20, 0, -1}, {1, 0, 0}}, 0, 100, work);
  ASSERT_TRUE(side.hit);
  EXPECT_FALSE(side.on_box_face);
  EXPECT_NEAR(side.t, 20 - std::sqrt(16 - 1), 1e-6);
}

TEST(ClipToBox, SlabsAndParallelRays) {
  const Box b({-1, -1, -1}, {1, 2, 3});
  double t0 = 0, t1 = 100;
  ASSERT_TRUE(clip_to_box({{-5, 0, 0}, {1, 0, 0}}, b, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 4);
  EXPECT_DOUBLE_EQ(t1, 6);
  t0 = 0, t1 = 100;
  EXPECT_FALSE(clip_to_box({{-5, 5, 0}, {1, 0, 0}}, b, t0, t1));
  t0 = 0, t1 = 3;
  EXPECT_FALSE(clip_to_box({{-5, 0, 0}, {1, 0, 0}}, b, t0, t1)) << "box beyond tfar";
}

}  // namespace
}  // namespace softtrace

// A shadow ray with no list, of a sum of at most BlobSum::kListed blobs (shadow_hit), is answered
// before first_hit_blobs where its whole way's terms sum their peaks below iso, and otherwise
// handed to it with those terms taken (few_blobs_shadow): the answer and the counted work must be
// first_hit's own to the bit. Each ray is traced both ways: from points beside the surface of the
// tracer scenes' sum of five ellipsoids and balls (lifted off it, as shadow rays start, and pushed
// into it) in random directions, and along random lines through the sum.
#include <gtest/gtest.h>

#include <random>

#include "same_march.h"
#include "scene/traced_objects.h"
#include "tracer_scenes.h"

namespace softtrace {
namespace {

using namespace tracer_scenes;

// The ray traced as a shadow ray by shadow_hit and by first_hit, as one assertion;
// `clear` counts the rays answered with no hit after one stretch (the short way's own answers),
// `read` those with no hit whose pieces were read (handed to first_hit_blobs with their terms).
::testing::AssertionResult shadow_both_ways(const ObjectTracer& tracer, const Ray& ray, double tfar,
                                            int* clear, int* read) {
  TraceCounters a, b;
  const MarchResult short_way = tracer.shadow_hit(ray, 0, tfar, a);
  const MarchResult long_way = tracer.first_hit(ray, 0, tfar, b, Query::Any);
  *clear += !short_way.hit && a.box_evals == 1;
  *read += !short_way.hit && a.box_evals > 1;
  if (a.point_evals != b.point_evals || a.give_ups != b.give_ups || a.entered_box != b.entered_box)
    return ::testing::AssertionFailure()
           << "point_evals " << a.point_evals << " against " << b.point_evals << ", give_ups "
           << a.give_ups << " against " << b.give_ups;
  return test::same_march(short_way, a, long_way, b);
}

TEST(FewBlobsShadow, AnsweredAsFirstHitBlobsAnswers) {
  const Scene scene = parse_scene(kScenes[kBlobs], "<test>");
  const SceneObject& obj = scene.objects[0];
  const ObjectTracer tracer(trace_target(obj), LipschitzMode::Local);
  ASSERT_TRUE(tracer.blob_sum());
  const std::optional<BlobSum> sum = BlobSum::of(tracer.program());
  ASSERT_TRUE(sum && sum->size() <= BlobSum::kListed);
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> u(-1, 1);
  const double R = obj.bounds.diagonal();
  int clear = 0, read = 0, blocked = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 d = normalize({u(rng), u(rng), u(rng)});
    const Vec3 target = obj.bounds.center() + Vec3{u(rng), u(rng), u(rng)} * 6;
    const Ray line{target - d * R, d};
    ASSERT_TRUE(shadow_both_ways(tracer, line, 2 * R, &clear, &read)) << "line " << i;
    TraceCounters w;
    const MarchResult m = tracer.first_hit(line, 0, 2 * R, w);
    if (!m.hit || m.gave_up) continue;
    for (const double lift : {-1e-4 * R, -1e-7 * R, 1e-4 * R}) {
      const Vec3 o = line.o + line.d * (m.t + lift);
      for (int k = 0; k < 8; ++k) {
        const Ray shadow{o, normalize({u(rng), u(rng), u(rng)}), 1e-4, 1e-3};
        ASSERT_TRUE(shadow_both_ways(tracer, shadow, 2 * R, &clear, &read))
            << "line " << i << " lift " << lift << " k " << k;
        TraceCounters a;
        blocked += tracer.shadow_hit(shadow, 0, 2 * R, a).hit;
      }
    }
  }
  // Each way is taken many times: the short way's answers, and first_hit_blobs' walks to a miss
  // and to a hit.
  EXPECT_GT(clear, 500);
  EXPECT_GT(read, 100);
  EXPECT_GT(blocked, 1000);
}

}  // namespace
}  // namespace softtrace

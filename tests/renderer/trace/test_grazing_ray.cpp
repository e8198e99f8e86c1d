// A ray that grazes a surface without entering it is decided, not passed undecided: the primary
// ray of scenes/fig003_9a_crossing_cylinders.json at 225x90 that runs 3e-7 of its footprint
// outside the bulge-eliminated blend, an oracle (g = -1.35e-7 over a stretch). The BT oracle gives
// no slope along a segment, so only the spheres of points and first-order intervals clear such a
// stretch, each a piece about 2|g|/L long: 2835 evaluations for its longest piece, more than the
// deep halving's old budget of 2000 (tracer_limits.h kDeepBudget).
#include <gtest/gtest.h>

#include <string>

#include "scene/scene.h"
#include "scene/traced_objects.h"
#include "trace/tracer.h"

namespace softtrace {
namespace {

TEST(GrazingRay, Fig003Fig9aGrazeIsDecidedClear) {
  const Scene scene =
      load_scene(std::string(SOFTTRACE_SOURCE_DIR) + "/scenes/fig003_9a_crossing_cylinders.json");
  const SceneObject* obj = nullptr;
  for (const SceneObject& o : scene.objects)
    if (o.name == "bulge_eliminated") obj = &o;
  ASSERT_NE(obj, nullptr);
  const ObjectTracer tr(trace_target(*obj), LipschitzMode::Local);
  // The camera ray as the renderer builds it (eye, unit direction, the pixel's cone).
  const Ray ray{{0, -22, 8},
                {0.018073891901949017, 0.94672777313342682, -0.32152738298524319},
                0,
                0.0022605811047077705};
  double t0 = 0, t1 = 1e9;
  ASSERT_TRUE(clip_to_box(ray, obj->bounds, t0, t1));
  TraceCounters work;
  const MarchResult m = tr.first_hit(ray, t0, t1, work);
  EXPECT_EQ(work.undecided, 0);
  EXPECT_EQ(work.give_ups, 0);
  EXPECT_FALSE(m.gave_up);
  // The graze: outside the solid all along it, by about 1.35e-7 in g.
  for (int i = 0; i <= 1000; ++i) {
    const double t = 23.4620 + 0.0001 * i / 1000;
    ASSERT_FALSE(tr.inside(ray.o + ray.d * t)) << "t = " << t;
  }
  if (m.hit) {
    EXPECT_GT(m.t, 23.4621) << "a hit at the graze would be an invented surface";
    EXPECT_TRUE(tr.inside(ray.o + ray.d * m.t));
  }
}

}  // namespace
}  // namespace softtrace

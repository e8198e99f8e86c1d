// The steps AOV (frame.cpp, centre_aovs): each pixel's centre ray's evaluations and those of its
// shadow rays, which the frame takes as what the tile's shadow count grew by while the sample was
// shaded. At one sample a pixel over a frame whose one object is a blob sum (whose beams count no
// work of their own: ObjectTracer::clear_depth), every camera and shadow ray is some pixel's
// centre ray's or one of its shadow rays, so the plane's sum must be the frame's count of
// evaluations (FrameStats::steps): each pixel's shadow rays counted, and counted once.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "render/frame.h"
#include "render/threads.h"
#include "scene/scene.h"
#include "sparse_ball_cloud.h"

namespace softtrace {
namespace {

// 400 balls seen from a corner: camera rays that meet several, and shadow rays with work of their
// own.
Scene ball_cloud() {
  return parse_scene(
      sparse_ball_cloud(
          400, 24, R"({"eye": [40, -55, 35], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 40})"),
      "<test>");
}

TEST(FrameSteps, ThePlaneSumsToTheFramesEvaluations) {
  const Scene scene = ball_cloud();
  const TracedScene rt(scene, LipschitzMode::Local);
  constexpr int kW = 96, kH = 72;
  Film film(kW, kH, AovSelection{false, false, true, false});
  RenderOptions opt;
  opt.spp = 1;
  FrameStats stats;
  ASSERT_TRUE(render_frame(scene, rt, opt, film, nullptr, &stats));
  long long sum = 0;
  for (const float s : film.steps) sum += static_cast<long long>(s);
  // Not vacuous: the shadow rays have evaluations of their own.
  EXPECT_GT(stats.shadow.evaluations(), 300);
  EXPECT_GT(stats.primary.evaluations(), 1000);
  EXPECT_EQ(sum, stats.steps);
}

// The frame's totals are sums over each thread's own (frame.cpp's Work): counts, so the same at 1,
// 2 and 8 threads, as the pixels are.
TEST(FrameSteps, TheTotalsAreTheSameAtAnyThreadCount) {
  const Scene scene = ball_cloud();
  const TracedScene rt(scene, LipschitzMode::Local);
  constexpr int kW = 96, kH = 72;
  RenderOptions opt;
  opt.spp = 1;
  FrameStats one;
  Film first(kW, kH, AovSelection{});
  run_on_threads(1, [&] { ASSERT_TRUE(render_frame(scene, rt, opt, first, nullptr, &one)); });
  EXPECT_GT(one.shadow.evaluations(), 300);
  for (const int threads : {2, 8}) {
    FrameStats many;
    Film film(kW, kH, AovSelection{});
    run_on_threads(threads,
                   [&] { ASSERT_TRUE(render_frame(scene, rt, opt, film, nullptr, &many)); });
    EXPECT_EQ(many.steps, one.steps) << threads << " threads";
    EXPECT_EQ(many.primary.evaluations(), one.primary.evaluations()) << threads << " threads";
    EXPECT_EQ(many.shadow.evaluations(), one.shadow.evaluations()) << threads << " threads";
    ASSERT_EQ(film.rgba.size(), first.rgba.size());
    EXPECT_EQ(
        std::memcmp(film.rgba.data(), first.rgba.data(), film.rgba.size() * sizeof(film.rgba[0])),
        0)
        << threads << " threads";
  }
}

}  // namespace
}  // namespace softtrace

// `softtrace bench`: a scene's frame rendered --repeat times without output, timed per frame, with
// the work per ray that enters an object box. The JSON (schema 1) is documented in docs/cli.md.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/cmd_common.h"
#include "cli/commands.h"
#include "cli/core_hand_over.h"
#include "commit.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/threads.h"

namespace softtrace {

namespace {

constexpr int kSchema = 1;

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

struct FrameTime {
  double wall_s, cpu_s;
};

// Work per ray that entered an object box (the rays that missed every box cost no evaluation).
nlohmann::json work_json(const RayWork& w) {
  const double n = static_cast<double>(std::max(1LL, w.entered_box));
  return {{"rays", w.rays},
          {"entered_box", w.entered_box},
          {"point_evals", w.point_evals / n},
          {"box_evals", w.box_evals / n},
          {"refine_iterations", w.refine_iterations / n},
          {"give_ups", w.give_ups},
          {"undecided", w.undecided},
          {"evaluations", w.evaluations() / n}};
}

void print_work(const char* kind, const RayWork& w) {
  const double n = static_cast<double>(std::max(1LL, w.entered_box));
  std::printf(
      "  %s rays: %lld, %lld enter a box; per such ray %.2f point + %.2f box = %.2f evaluations, "
      "%.2f refinement iterations, %lld gave up, %lld undecided\n",
      kind, w.rays, w.entered_box, w.point_evals / n, w.box_evals / n, w.evaluations() / n,
      w.refine_iterations / n, w.give_ups, w.undecided);
}

}  // namespace

int run_bench(const BenchArgs& a) {
  try {
    Scene scene = load_scene(a.scene);
    hand_over_embree_scene(scene);  // the static program's, before the compile (core_hand_over.h)
    apply_image_size(scene, a.scene, a.width, a.height, a.scale);
    apply_camera_options(scene, a.view);
    const auto limit = limit_threads(a.threads);
    const int threads = a.threads ? a.threads : default_threads();
    const TracedScene rt(scene, a.lipschitz);
    release_standard_error();  // nothing from here on needs softtrace-core (core_hand_over.h)
    RenderOptions opt;
    opt.lipschitz = a.lipschitz;
    std::vector<FrameTime> frames;
    FrameStats stats;  // the same every frame: each pixel's work depends on the pixel alone
    // One bar for all frames; drawing it costs a few microseconds ten times a second.
    Progress progress("bench", long(a.repeat) * scene.image.width * scene.image.height,
                      !a.quiet && (a.progress || ::isatty(2)),
                      samples_per_pixel(scene.camera, scene.image.spp));
    for (int i = 0; i < a.repeat; ++i) {
      Film film(scene.image.width, scene.image.height, AovSelection{});
      const double c0 = process_cpu_seconds();
      const auto t0 = std::chrono::steady_clock::now();
      render_frame(scene, rt, opt, film, &progress, &stats);
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      frames.push_back({wall, process_cpu_seconds() - c0});
    }
    progress.finish();

    std::vector<double> secs;
    for (const FrameTime& f : frames) secs.push_back(f.wall_s);
    std::sort(secs.begin(), secs.end());
    const double best = secs.front(), median = secs[secs.size() / 2];
    const double rays = static_cast<double>(stats.primary_rays);
    const double evals = static_cast<double>(stats.steps) / std::max(1.0, rays);
    const char* mode = a.lipschitz == LipschitzMode::Local ? "local" : "global";
    if (a.json) {
      nlohmann::json per_frame = nlohmann::json::array();
      for (const FrameTime& f : frames)
        per_frame.push_back(
            {{"wall_s", f.wall_s}, {"cpu_s", f.cpu_s}, {"mrays_per_s", rays / f.wall_s * 1e-6}});
      const nlohmann::json out = {{"schema", kSchema},
                                  {"version", SOFTTRACE_VERSION},
                                  {"commit", SOFTTRACE_COMMIT},
                                  {"scene", a.scene},
                                  {"width", scene.image.width},
                                  {"height", scene.image.height},
                                  {"spp", scene.image.spp},
                                  {"threads", threads},
                                  {"lipschitz", mode},
                                  {"repeat", a.repeat},
                                  {"frames", per_frame},
                                  {"best_s", best},
                                  {"median_s", median},
                                  {"mrays_per_s", rays / best * 1e-6},
                                  {"evaluations_per_ray", evals},
                                  {"primary", work_json(stats.primary)},
                                  {"shadow", work_json(stats.shadow)}};
      std::printf("%s\n", out.dump().c_str());
    } else {
      std::printf("%s: %dx%d, %d spp, %d threads, lipschitz %s, commit %s\n", a.scene.c_str(),
                  scene.image.width, scene.image.height, scene.image.spp, threads, mode,
                  SOFTTRACE_COMMIT);
      for (size_t i = 0; i < frames.size(); ++i)
        std::printf("  frame %zu: wall %.4f s, cpu %.4f s, %.3f M primary rays/s\n", i + 1,
                    frames[i].wall_s, frames[i].cpu_s, rays / frames[i].wall_s * 1e-6);
      std::printf("  best %.4f s, median %.4f s, %.3f M primary rays/s, %.1f evaluations/ray\n",
                  best, median, rays / best * 1e-6, evals);
      print_work("primary", stats.primary);
      print_work("shadow", stats.shadow);
    }
    return 0;
  } catch (const std::exception& e) {
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

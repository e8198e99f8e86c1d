// `softtrace bench`: primary-ray throughput of a scene, shading included, without output.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cmd_common.h"
#include "commands.h"
#include "frame.h"

namespace softtrace {

int run_bench(const BenchArgs& a) {
  try {
    Scene scene = load_scene(a.scene);
    apply_image_size(scene, a.scene, a.width, a.height);
    const auto threads = limit_threads(a.threads);
    const TracedScene rt(scene, a.lipschitz);
    RenderOptions opt;
    opt.lipschitz = a.lipschitz;
    std::vector<double> secs;
    FrameStats stats;
    // One bar for all frames; drawing it costs a few microseconds ten times a second.
    Progress progress("bench", long(a.repeat) * scene.image.width * scene.image.height,
                      !a.quiet && (a.progress || ::isatty(2)), scene.image.spp);
    for (int i = 0; i < a.repeat; ++i) {
      Film film(scene.image.width, scene.image.height);
      const auto t0 = std::chrono::steady_clock::now();
      render_frame(scene, rt, opt, film, &progress, &stats);
      secs.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    progress.finish();
    std::sort(secs.begin(), secs.end());
    const double best = secs.front(), median = secs[secs.size() / 2];
    const double rays = static_cast<double>(stats.primary_rays);
    const double evals = static_cast<double>(stats.steps) / std::max(1.0, rays);
    const char* mode = a.lipschitz == LipschitzMode::Local ? "local" : "global";
    if (a.json) {
      const nlohmann::json out = {{"scene", a.scene},
                                  {"width", scene.image.width},
                                  {"height", scene.image.height},
                                  {"spp", scene.image.spp},
                                  {"lipschitz", mode},
                                  {"frames", a.repeat},
                                  {"best_s", best},
                                  {"median_s", median},
                                  {"mrays_per_s", rays / best * 1e-6},
                                  {"evaluations_per_ray", evals}};
      std::printf("%s\n", out.dump().c_str());
    } else {
      std::printf("%s: %dx%d, %d spp, lipschitz %s, %d frames\n", a.scene.c_str(),
                  scene.image.width, scene.image.height, scene.image.spp, mode, a.repeat);
      std::printf("  best %.4f s, median %.4f s, %.3f M primary rays/s, %.1f evaluations/ray\n",
                  best, median, rays / best * 1e-6, evals);
    }
    return 0;
  } catch (const std::exception& e) {
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

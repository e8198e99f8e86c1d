#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "film.h"
#include "frame.h"

namespace softtrace {

void report_error(const std::string& message) {
  std::fprintf(stderr, "softtrace: %s\n", message.c_str());
}

namespace {

std::atomic<bool> g_cancel{false};
std::atomic<bool> g_writing{false};

// SIGINT/SIGTERM: stop rendering; while an image is being written, drop its temporary file and
// leave at once, so neither a partial image nor a clobbered existing file remains.
extern "C" void on_signal(int sig) {
  g_cancel = true;
  if (g_writing) {
    abandon_pending_writes();
    _exit(128 + sig);
  }
}

}  // namespace

int run_render(const RenderArgs& a) {
  try {
    Scene scene = load_scene(a.scene);
    if (a.width) scene.image.width = a.width;
    if (a.height) scene.image.height = a.height;
    if (a.spp) scene.image.spp = a.spp;
    if (static_cast<long long>(scene.image.width) * scene.image.height > (1LL << 26))
      throw SceneError(a.scene + ": /image: more than 2^26 pixels requested");

    const AovSelection aovs = parse_aovs(a.aovs);
    std::vector<std::string> outputs = a.outputs;
    if (outputs.empty()) outputs.push_back(std::filesystem::path(a.scene).stem().string() + ".exr");
    for (const auto& o : outputs) check_output_path(o);  // fail before the work, not after
    if ((aovs.depth || aovs.normal || aovs.steps) &&
        std::none_of(outputs.begin(), outputs.end(), is_exr_path))
      throw std::invalid_argument("--aov needs an .exr output");

    std::unique_ptr<tbb::global_control> threads;
    if (a.threads)
      threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      a.threads);

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);

    const auto start = std::chrono::steady_clock::now();
    const EmbreeScene rt(scene, a.lipschitz);
    Film film(scene.image.width, scene.image.height);
    Progress progress("rendering", long(film.width) * film.height, !a.quiet && ::isatty(2));
    RenderOptions opt;
    opt.lipschitz = a.lipschitz;
    opt.cancel = &g_cancel;
    FrameStats stats;
    const bool complete = render_frame(scene, rt, opt, film, &progress, &stats);
    progress.finish();
    if (!complete) {
      report_error("interrupted; no image written");
      return 130;
    }
    g_writing = true;
    for (const auto& o : outputs) write_image(o, film, aovs);
    g_writing = false;
    if (g_cancel) return 130;

    if (!a.quiet) {
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "%dx%d, %d spp in %.2f s (%.2f M primary rays/s, %.1f evaluations/ray)",
                   film.width, film.height, scene.image.spp, secs, stats.primary_rays / secs * 1e-6,
                   static_cast<double>(stats.steps) / std::max(1LL, stats.primary_rays));
      for (const auto& o : outputs) std::fprintf(stderr, " -> %s", o.c_str());
      std::fprintf(stderr, "\n");
    }
    return 0;
  } catch (const std::exception& e) {
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

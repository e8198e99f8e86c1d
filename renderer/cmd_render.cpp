#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cmd_common.h"
#include "commands.h"
#include "film.h"
#include "frame.h"
#include "frame_metadata.h"

namespace softtrace {

void report_error(const std::string& message) {
  std::fprintf(stderr, "softtrace: %s\n", message.c_str());
}

namespace {

std::atomic<bool> g_cancel{false};
std::atomic<int> g_signal{0};

// What a signal does depends on the phase. Loading (until the frame starts): nothing exists
// yet, so exit at once, even in the middle of a long load. Rendering: stop the frame (g_cancel)
// and write nothing. Writing temporary files: remove them and exit at once. Committing (renaming
// the finished files over the outputs): nothing, so that all outputs are replaced or none is.
// The compare-exchanges decide between the watcher and the main thread who owns a transition.
enum Phase : int { kLoading, kRendering, kWriting, kCommitting, kAborting };
std::atomic<int> g_phase{kLoading};

}  // namespace

void on_render_interrupt(int sig) {
  int none = 0;
  g_signal.compare_exchange_strong(none, sig);
  g_cancel = true;
  int phase = kLoading;
  if (g_phase.compare_exchange_strong(phase, kAborting)) {
    report_error("interrupted; no image written");
    abandon_pending_writes_and_exit(128 + sig);
  }
  phase = kWriting;
  if (g_phase.compare_exchange_strong(phase, kAborting)) abandon_pending_writes_and_exit(128 + sig);
}

namespace {

int interrupted_status() {
  return 128 + g_signal.load();
}

}  // namespace

int run_render(const RenderArgs& a) {
  // main() has started the signal watcher with on_render_interrupt.
  try {
    Scene scene = load_scene(a.scene);
    apply_image_size(scene, a.scene, a.width, a.height);
    if (a.spp) scene.image.spp = a.spp;

    OutputOptions out_opt;
    out_opt.aovs = parse_aovs(a.aovs);
    out_opt.flatten = a.flatten;
    out_opt.half = a.half;
    out_opt.png_alpha = a.png_alpha;
    const AovSelection& aovs = out_opt.aovs;
    std::vector<std::string> outputs = a.outputs;
    if (outputs.empty()) outputs.push_back(std::filesystem::path(a.scene).stem().string() + ".exr");
    for (const auto& o : outputs) check_image_output_path(o);  // fail before the work, not after
    if ((aovs.depth || aovs.normal || aovs.steps) &&
        std::none_of(outputs.begin(), outputs.end(), is_exr_path))
      throw std::invalid_argument("--aov needs an .exr output");

    const auto threads = limit_threads(a.threads);

    const auto start = std::chrono::steady_clock::now();
    const TracedScene rt(scene, a.lipschitz);
    int loading = kLoading;
    if (!g_phase.compare_exchange_strong(loading, kRendering))
      for (;;) ::pause();  // the watcher is exiting
    Film film(scene.image.width, scene.image.height);
    FrameInfo info = frame_info(scene, film.full_width, film.full_height);
    Progress progress("rendering", long(film.width) * film.height,
                      !a.quiet && (a.progress || ::isatty(2)), scene.image.spp);
    RenderOptions opt;
    opt.lipschitz = a.lipschitz;
    opt.cancel = &g_cancel;
    FrameStats stats;
    const bool complete = render_frame(scene, rt, opt, film, &progress, &stats);
    progress.finish();
    if (!complete) {
      report_error("interrupted; no image written");
      return interrupted_status();
    }
    g_phase = kWriting;
    if (g_cancel) {  // the signal came after the last pixel but before the phase changed
      report_error("interrupted; no image written");
      return interrupted_status();
    }
    info.render_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<std::string> temps;
    for (const auto& o : outputs) temps.push_back(write_image_temp(o, film, out_opt, info));
    int writing = kWriting;
    if (!g_phase.compare_exchange_strong(writing, kCommitting))
      for (;;) ::pause();  // the watcher is removing the temporary files and exiting
    for (size_t i = 0; i < outputs.size(); ++i) commit_image(temps[i], outputs[i]);
    forget_pending_writes();
    // A signal from here on is too late to matter: every output is complete.

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
    abandon_pending_writes();  // a failed write leaves no temporary file behind
    forget_pending_writes();
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cli/cmd_common.h"
#include "cli/commands.h"
#include "cli/core_hand_over.h"
#include "cli/exr_on_demand.h"
#include "cli/heap_pages.h"
#include "cli/load_arena.h"
#include "cli/option_checks.h"
#include "cli/signals.h"
#include "describe/params.h"
#include "film/film.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/frame_metadata.h"
#include "render/threads.h"
#include "render/tiles.h"

namespace softtrace {

void report_error(const std::string& message) {
  // One line whatever the message quotes (a file name with a newline, say; SceneError's are
  // printable already).
  std::fprintf(stderr, "softtrace: %s\n", printable(message).c_str());
}

namespace {

std::atomic<bool> g_cancel{false};
std::atomic<int> g_signal{0};

// What a signal does depends on the phase. Loading (until the frame starts): nothing exists
// yet, so exit at once, even in the middle of a long load. Rendering: stop the frame (g_cancel)
// and write nothing. Writing temporary files: remove them and exit at once. Committing (renaming
// the finished files over the outputs): nothing, so that all outputs are replaced or none is.
// The compare-exchanges decide between the handler (on whichever thread the signal interrupts)
// and the main thread who owns a transition.
enum Phase : int { kLoading, kRendering, kWriting, kCommitting, kAborting };
std::atomic<int> g_phase{kLoading};

}  // namespace

void on_render_interrupt(int sig) {
  int none = 0;
  g_signal.compare_exchange_strong(none, sig);
  g_cancel = true;
  int phase = kLoading;
  if (g_phase.compare_exchange_strong(phase, kAborting)) {
    report_from_handler("softtrace: interrupted; no image written\n");  // report_error's line
    abandon_pending_writes_and_exit(128 + sig);
  }
  phase = kWriting;
  if (g_phase.compare_exchange_strong(phase, kAborting)) abandon_pending_writes_and_exit(128 + sig);
}

namespace {

// A worker's heap in huge pages: meets1's worker touched 600 KB of its arena at 320x240 (the
// first huge page, filled at its start), what takes more has a second.
constexpr size_t kWorkerHeapBytes = size_t(4) << 20;

void worker_start() {
  thread_heap_in_huge_pages(kWorkerHeapBytes);
}

bool is_png_output(const std::string& path) {
  return !is_exr_path(path);
}

int interrupted_status() {
  return 128 + g_signal.load();
}

// `pattern` with its last run of '#' replaced by the frame number, zero-padded to the run's
// length: "turn.####.exr" -> "turn.0007.exr". Without --frame a '#' is refused rather than kept,
// since it almost always means a frame was forgotten.
std::string frame_path(const std::string& pattern, int frame) {
  const size_t end = pattern.find_last_of('#');
  if (end == std::string::npos) return pattern;
  if (frame < 0) throw std::invalid_argument(pattern + ": '#' stands for the frame: give --frame");
  size_t begin = end;
  while (begin > 0 && pattern[begin - 1] == '#') --begin;
  std::string number = std::to_string(frame);
  if (number.size() < end + 1 - begin) number.insert(0, end + 1 - begin - number.size(), '0');
  return pattern.substr(0, begin) + number + pattern.substr(end + 1);
}

// Whether any pixel of the film shows an object (coverage A > 0 anywhere).
bool shows_an_object(const Film& film) {
  for (size_t i = 3; i < film.rgba.size(); i += 4)
    if (film.rgba[i] > 0) return true;
  return false;
}

// The part of the frame to render: --crop, --pixel-bounds or --tile (at most one), or all.
PixelBounds window_of(const RenderArgs& a, int width, int height) {
  if (a.crop) return crop_window(*a.crop, width, height);
  if (a.pixel_bounds) return pixel_bounds(*a.pixel_bounds, width, height);
  if (a.tile) return tile_bounds(parse_tile(*a.tile), width, height);
  return {0, width, 0, height};
}

// Ends the process once every output is committed, without the destructors of the scene, the
// tracers and the film nor the worker threads' end (TBB's teardown took 0.4 ms of CPU on a small
// frame): what they would free, the kernel takes back at once. A sanitizer build returns instead,
// so that its leak check sees the whole run.
#if defined(__SANITIZE_ADDRESS__)
#define SOFTTRACE_FULL_TEARDOWN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOFTTRACE_FULL_TEARDOWN 1
#endif
#endif
int finish_process(int status) {
#ifndef SOFTTRACE_FULL_TEARDOWN
  std::fflush(stdout);
  std::fflush(stderr);
  ::_exit(status);
#endif
  return status;
}

}  // namespace

int run_render(const RenderArgs& a) {
  // main() has made on_render_interrupt the signals' handler.
  try {
    // The cap, kept until exit (a smaller one may be kept after it), and the frame's worker
    // threads started beside the scene's load, which they do not wait for (threads.h).
    if (a.threads) limit_threads(a.threads).keep_until_exit();
    // The workers keep the signals blocked, so that the handler runs on this thread. Each puts its
    // heap in huge pages while this thread loads the scene (heap_pages.h).
    block_interrupts();
    start_threads(worker_start);
    unblock_interrupts();
    // The load's blocks from the arena (load_arena.h): the scene and its document stay until
    // exit, which does not free them.
    Scene scene = [&] {
      const LoadArena arena;
      return load_scene(a.scene);
    }();
    hand_over_embree_scene(scene);  // the static program's, before the checks and the compile
    apply_image_size(scene, a.scene, a.width, a.height, a.scale);
    if (a.spp) scene.image.spp = a.spp;
    if (a.antialias) scene.image.antialias.threshold = *a.antialias;
    if (a.frame >= 0) set_frame(scene, a.frame);
    apply_camera_options(scene, a.view);
    const PixelBounds window = window_of(a, scene.image.width, scene.image.height);

    OutputOptions out_opt;
    out_opt.aovs = parse_aovs(a.aovs);
    out_opt.flatten = a.flatten;
    out_opt.half = a.half;
    out_opt.png_alpha = a.png_alpha;
    const AovSelection& aovs = out_opt.aovs;
    std::vector<std::string> outputs;
    for (const auto& o : a.outputs) outputs.push_back(frame_path(o, a.frame));
    if (outputs.empty())
      outputs.push_back(frame_path(
          std::filesystem::path(a.scene).stem().string() + (a.frame >= 0 ? ".####.exr" : ".exr"),
          a.frame));
    for (const auto& o : outputs) check_image_output_path(o);  // fail before the work, not after
    // The EXR module as well, named as the first EXR's write would name it.
    const auto first_exr = std::find_if(outputs.begin(), outputs.end(), is_exr_path);
    try {
      if (first_exr != outputs.end()) load_exr_module();
    } catch (const std::exception& e) {
      throw std::runtime_error(*first_exr + ": " + e.what());
    }
    if ((aovs.depth || aovs.normal || aovs.steps || aovs.albedo) &&
        std::none_of(outputs.begin(), outputs.end(), is_exr_path))
      throw std::invalid_argument("--aov needs an .exr output");

    // No more threads than the frame has tiles (the same bits for any count, frame.h): a smaller
    // cap beside --threads' (the process exits after the frame).
    const int tasks = frame_tasks(window.x0, window.y0, window.width(), window.height());
    const int wanted = a.threads ? a.threads : default_threads();
    if (wanted > tasks) limit_threads(tasks).keep_until_exit();

    const auto start = std::chrono::steady_clock::now();
    // The film's planes are zeroed as they are made, a page fault per 4 KiB of fresh memory (300
    // at 320x240, about 0.3 ms): a worker thread makes them while this one builds the tracers.
    std::optional<TracedScene> traced;
    std::optional<Film> made;
    parallel_each(2, [&](size_t i) {
      if (i == 0)
        traced.emplace(scene, a.lipschitz);
      else
        made.emplace(window.width(), window.height(), aovs);
    });
    // Nothing from here on needs softtrace-core: what the static program held is printed now,
    // before the progress bar asks whether standard error is a terminal.
    release_standard_error();
    const TracedScene& rt = *traced;
    Film& film = *made;
    int loading = kLoading;
    if (!g_phase.compare_exchange_strong(loading, kRendering))
      for (;;) ::pause();  // a handler on another thread is exiting
    film.full_width = scene.image.width;
    film.full_height = scene.image.height;
    film.x0 = window.x0;
    film.y0 = window.y0;
    // Only an EXR's header carries the scene's hash and the render hash: a PNG-only run does not
    // hash the scene's bytes.
    const bool exr = std::any_of(outputs.begin(), outputs.end(), is_exr_path);
    FrameInfo info = frame_info(scene, film.full_width, film.full_height, /*with_hash=*/false);
    const uint64_t file_hash = exr ? scene.file_hash() : 0;
    if (exr) info.scene_hash = hex64(file_hash);
    // What `merge` checks before it puts tiles together.
    // --flatten and --half change the EXR's pixels: tiles rendered with and without them must not
    // be merged.
    std::string settings =
        render_settings(scene, a.lipschitz == LipschitzMode::Local ? "local" : "global", a.frame);
    if (a.flatten) settings += " flatten";
    if (a.view.eye) settings += " eye=" + *a.view.eye;
    if (a.view.target) settings += " target=" + *a.view.target;
    if (a.view.fov) {
      char fov[32];
      std::snprintf(fov, sizeof fov, " fov=%.17g", *a.view.fov);
      settings += fov;
    }
    if (a.half) settings += " half";
    if (exr) film.attributes["softtrace/renderHash"] = render_hash(file_hash, settings);
    film.attributes["softtrace/render"] = settings;
    if (a.tile) film.attributes["softtrace/tile"] = *a.tile;
    if (a.frame >= 0) film.attributes["softtrace/frame"] = std::to_string(a.frame);
    // The samples a pixel takes (a lens's blur_samples may exceed the image's spp): what the
    // progress and the summary's rays/s count.
    const int spp = samples_per_pixel(scene.camera, scene.image.spp);
    Progress progress("rendering", long(film.width) * film.height,
                      !a.quiet && (a.progress || ::isatty(2)), spp);
    RenderOptions opt;
    opt.lipschitz = a.lipschitz;
    opt.cancel = &g_cancel;
    // The PNG's bands (the same for every PNG output) are deflated by the threads that trace the
    // frame, each as soon as the tiles over its rows are done, so that the second thread shares
    // them and only the last tile row's band or two are left after the frame. At 320x240 they had
    // been the main thread's alone after the frame (1.2-1.6 ms, the worker ended), as overlapping
    // them had measured longer under a load of 12 (session 40); without the load's queueing
    // (processes at real-time priority, 3 rounds of 30-40 alternating pairs, session 41) molecule,
    // candle and old_syntax took 0.2-0.8 ms less a process, meets1 0.0-0.2 ms less.
    std::unique_ptr<PngBands> png;
    if (std::any_of(outputs.begin(), outputs.end(), is_png_output)) {
      png = film_png_bands(film, out_opt, info);
      opt.pixels_final = [&png](int y0, int y1, int width) { png->pixels_final(y0, y1, width); };
    }
    FrameStats stats;
    // The workers end after their last loop, so that the exit has one thread to end, not a
    // sleeping one to wake first (threads.h): after the frame's loops (two with adaptive
    // anti-aliasing, frame.h), which leave the PNG's bands deflated but the last ones.
    end_threads_after_loops(scene.image.antialias.on() ? 2 : 1);
    const bool complete = render_frame(scene, rt, opt, film, &progress, &stats);
    progress.finish();
    if (!complete) {
      report_error("interrupted; no image written");
      return interrupted_status();
    }
    // A whole frame with nothing in it is almost always a camera that looks away or a scene in
    // other units: say so (a warning, as the loader's; --quiet silences only progress and the
    // summary). A part of a frame may well show only background.
    const bool whole_frame = film.width == film.full_width && film.height == film.full_height;
    if (whole_frame && !shows_an_object(film))
      std::fprintf(stderr,
                   "softtrace: warning: no object is visible in the frame, the image shows only "
                   "the background (check the camera's eye, target and fov against the "
                   "objects)\n");
    g_phase = kWriting;
    if (g_cancel) {  // the signal came after the last pixel but before the phase changed
      report_error("interrupted; no image written");
      return interrupted_status();
    }
    info.render_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<std::string> temps;
    for (const auto& o : outputs)
      temps.push_back(write_image_temp(o, film, out_opt, info, parallel_each, png.get()));
    int writing = kWriting;
    if (!g_phase.compare_exchange_strong(writing, kCommitting))
      for (;;) ::pause();  // a handler is removing the temporary files and exiting
    for (size_t i = 0; i < outputs.size(); ++i) commit_image(temps[i], outputs[i]);
    forget_pending_writes();
    // A signal from here on is too late to matter: every output is complete.

    if (!a.quiet) {
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "%dx%d", film.width, film.height);
      if (film.width != film.full_width || film.height != film.full_height)
        std::fprintf(stderr, " (x %d..%d, y %d..%d of %dx%d)", window.x0, window.x1 - 1, window.y0,
                     window.y1 - 1, film.full_width, film.full_height);
      std::fprintf(stderr, ", %d spp in %.2f s (%.2f M primary rays/s, %.1f evaluations/ray)", spp,
                   secs, stats.primary_rays / secs * 1e-6,
                   static_cast<double>(stats.steps) / std::max(1LL, stats.primary_rays));
      if (scene.image.antialias.on())
        std::fprintf(stderr, ", %lld pixels anti-aliased", stats.refined_pixels);
      for (const auto& o : outputs) std::fprintf(stderr, " -> %s", o.c_str());
      std::fprintf(stderr, "\n");
    }
    return finish_process(0);
  } catch (const std::exception& e) {
    abandon_pending_writes();  // a failed write leaves no temporary file behind
    forget_pending_writes();
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

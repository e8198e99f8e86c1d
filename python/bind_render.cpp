// softtrace._native.render: a frame of a scene to numpy arrays (and files), with Ctrl-C and a
// progress callback. The frame is traced on a worker thread while the calling thread, holding
// the GIL in short turns, checks for signals (PyErr_CheckSignals acts only on the main thread,
// where Python runs its handlers) and reports progress; a KeyboardInterrupt or an exception of
// the callback sets the renderer's cancel flag, which the tracer checks before every sample.
// The render holds its own reference to the scene and takes the image settings by value (the
// film's size, RenderOptions::spp), so threads rendering one Scene at different sizes never see
// each other's: nothing here writes to the scene.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "bindings.h"
#include "film/film.h"
#include "render/frame.h"
#include "render/frame_metadata.h"
#include "render/threads.h"

namespace softtrace::python {

namespace {

using namespace std::chrono_literals;

// How often the calling thread wakes to check signals and report progress.
constexpr auto kPoll = 20ms;

struct Request {
  int width = 0, height = 0, spp = 0, threads = 0;
  int frame = -1;  // an animation's frame; -1: the scene's camera
  std::vector<std::string> aovs, outputs;
  py::object progress;
  bool flatten = false;
};

AovSelection aovs_named(const std::vector<std::string>& names) {
  AovSelection a;
  for (const std::string& name : names) {
    if (name.empty())
      throw std::invalid_argument("unknown AOV '' (expected depth, normal, steps, albedo)");
    const AovSelection one = parse_aovs(name);
    a.depth |= one.depth;
    a.normal |= one.normal;
    a.steps |= one.steps;
    a.albedo |= one.albedo;
  }
  return a;
}

// The frame traced on its own thread; joined (after a cancel) whatever way the caller leaves.
class FrameJob {
 public:
  FrameJob(const Scene& scene, Film& film, int spp, int threads, Progress& progress) {
    opt_.cancel = &cancel_;
    opt_.spp = spp;
    worker_ = std::thread([this, &scene, &film, threads, &progress] {
      try {
        run_on_threads(threads, [&] {
          const TracedScene rt(scene, LipschitzMode::Local);
          complete_ = render_frame(scene, rt, opt_, film, &progress, nullptr);
        });
      } catch (...) {
        error_ = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
      done_.notify_all();
    });
  }
  ~FrameJob() {
    cancel_ = true;
    py::gil_scoped_release release;  // the worker never takes the GIL, but others may want it
    worker_.join();
  }

  // Waits up to `timeout` with the GIL released; true when the frame is finished.
  bool wait(std::chrono::milliseconds timeout) {
    py::gil_scoped_release release;
    std::unique_lock<std::mutex> lock(mutex_);
    return done_.wait_for(lock, timeout, [this] { return finished_; });
  }
  void cancel() { cancel_ = true; }
  // After wait() returned true: rethrows the worker's exception; false when cancelled.
  bool result() const {
    if (error_) std::rethrow_exception(error_);
    return complete_;
  }

 private:
  std::atomic<bool> cancel_{false};
  RenderOptions opt_;
  std::mutex mutex_;
  std::condition_variable done_;
  bool finished_ = false, complete_ = false;
  std::exception_ptr error_;
  std::thread worker_;
};

// Traces the film, calling `progress(done, total)` (pixels) as it goes.
void trace(const Scene& scene, Film& film, int spp, const Request& r) {
  const long total = long(film.width) * film.height;
  Progress progress("rendering", total, false);
  FrameJob job(scene, film, spp, r.threads, progress);
  long reported = -1;
  for (bool finished = false; !finished;) {
    finished = job.wait(kPoll);
    if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt, or what a handler raised
      job.cancel();
      throw py::error_already_set();
    }
    const long done = progress.done();
    if (!r.progress.is_none() && done != reported) {
      reported = done;
      try {
        r.progress(done, total);
      } catch (...) {
        job.cancel();
        throw;
      }
    }
  }
  if (!job.result()) throw std::runtime_error("the render was cancelled");
}

py::array_t<float> array_of(const FilmPlane& plane, const Film& film, size_t depth) {
  std::vector<size_t> shape{size_t(film.height), size_t(film.width)};
  if (depth > 1) shape.push_back(depth);
  py::array_t<float> out(shape);
  std::copy(plane.begin(), plane.end(), out.mutable_data());
  return out;
}

py::dict render(const PyScene& shared, const Request& r) {
  if (r.width < 0 || r.height < 0 || r.spp < 0 || r.width > 16384 || r.height > 16384 ||
      r.spp > 4096)
    throw std::invalid_argument("width and height must be in [1, 16384] and spp in [1, 4096]");
  if (r.threads < 0) throw std::invalid_argument("threads must be >= 0 (0: all cores)");
  // This render's reference: a setting changed meanwhile replaces shared.scene, not this one.
  std::shared_ptr<const Scene> held = shared.scene;
  if (r.frame >= 0) {
    // The frame's camera (and default lights) go into a scene of this render's own, parsed from
    // the same text: the shared one is never set to a frame, and the hash stays the text's.
    auto own = std::make_shared<Scene>(parse_scene(shared.text, held->path));
    set_frame(*own, r.frame);
    held = std::move(own);
  }
  const Scene& scene = *held;
  ImageSettings image = scene.image;  // this render's own
  // One of width and height alone keeps the scene's aspect, as --width or --height alone does.
  if (r.width) image.width = r.width;
  if (r.height) image.height = r.height;
  if (r.width && !r.height)
    image.height =
        int(std::max(1L, std::lround(double(r.width) * scene.image.height / scene.image.width)));
  if (r.height && !r.width)
    image.width =
        int(std::max(1L, std::lround(double(r.height) * scene.image.width / scene.image.height)));
  if (r.spp) image.spp = r.spp;
  check_pixel_count(image, scene.path);
  OutputOptions opt;
  opt.aovs = aovs_named(r.aovs);
  opt.flatten = r.flatten;
  for (const auto& o : r.outputs) check_image_output_path(o);  // before the work, as the CLI

  const auto start = std::chrono::steady_clock::now();
  Film film(image.width, image.height, opt.aovs);
  if (r.frame >= 0) film.attributes["softtrace/frame"] = std::to_string(r.frame);
  trace(scene, film, image.spp, r);
  {
    // The files as `softtrace render -o` writes them: all or nothing. The pending files are
    // this thread's (output_file.h), so a failure here removes only this render's.
    py::gil_scoped_release release;
    try {
      FrameInfo info = frame_info(scene, film.full_width, film.full_height);
      info.spp = image.spp;
      info.render_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::vector<std::string> temps;
      for (const auto& o : r.outputs) temps.push_back(write_image_temp(o, film, opt, info));
      for (size_t i = 0; i < r.outputs.size(); ++i) commit_image(temps[i], r.outputs[i]);
      forget_pending_writes();
    } catch (...) {
      abandon_pending_writes();
      throw;
    }
  }

  if (r.flatten) {  // over the background, as --flatten writes it
    for (size_t i = 0; i < film.rgba.size(); i += 4) {
      for (int k = 0; k < 3; ++k)
        film.rgba[i + k] += float(scene.background[k]) * (1 - film.rgba[i + 3]);
      film.rgba[i + 3] = 1;
    }
  }
  py::dict out;
  out["rgba"] = array_of(film.rgba, film, 4);
  if (opt.aovs.depth) out["depth"] = array_of(film.depth, film, 1);
  if (opt.aovs.normal) out["normal"] = array_of(film.normal, film, 3);
  if (opt.aovs.steps) out["steps"] = array_of(film.steps, film, 1);
  if (opt.aovs.albedo) out["albedo"] = array_of(film.albedo, film, 3);
  return out;
}

}  // namespace

void bind_render(py::module_& m) {
  m.def(
      "render",
      [](const PyScene& scene, int width, int height, int spp, int frame,
         std::vector<std::string> aovs, int threads, py::object progress, bool flatten,
         std::vector<std::string> outputs) {
        Request r;
        r.frame = frame;
        r.width = width;
        r.height = height;
        r.spp = spp;
        r.aovs = std::move(aovs);
        r.threads = threads;
        r.progress = std::move(progress);
        r.flatten = flatten;
        r.outputs = std::move(outputs);
        return render(scene, r);
      },
      py::arg("scene"), py::arg("width"), py::arg("height"), py::arg("spp"), py::arg("frame"),
      py::arg("aovs"), py::arg("threads"), py::arg("progress"), py::arg("flatten"),
      py::arg("outputs"));
}

}  // namespace softtrace::python

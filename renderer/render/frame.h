// Pixel -> beam -> tile -> frame: the frame is a parallel loop over tiles (render/threads.h), each
// tile a nest of beams (blocks of pixels whose approach to each object is certified together).
// Every pixel depends only on its own rays and its blocks, which are placed in the full frame, so
// the result is the same bits for any thread count, and a crop of the frame has the same bits as
// those pixels of the whole frame. With adaptive anti-aliasing the frame is two such loops: every
// pixel of the data window and a one-pixel apron, then the marked pixels again
// (render/antialias.h).
#pragma once

#include <atomic>
#include <functional>

#include "film/film.h"
#include "render/progress.h"
#include "render/threads.h"
#include "scene/traced_objects.h"
#include "trace/embree_scene.h"

namespace softtrace {

struct RenderOptions {
  LipschitzMode lipschitz = LipschitzMode::Local;
  // Stops the frame early when set: checked before every sample, light and secondary ray
  // (render/cancel.h), so that even a sample of a 10,000-child blend under area lights (thousands
  // of shadow rays) is no longer than one ray's wait.
  const std::atomic<bool>* cancel = nullptr;
  // Samples per pixel; 0: the scene's. A caller sharing the scene between threads (Python)
  // passes its own here rather than writing it into the scene.
  int spp = 0;
  // Told of the pixels each tile of the frame's last pass has made final, on the tile's thread, in
  // the caller's floating-point mode: `width` pixels of each of the data window's rows [y0, y1)
  // (0: its top row); every pixel once in a frame not cancelled. The command line's PNG deflates
  // the bands whose rows are final while the other tiles are traced (io/png_bands.h).
  std::function<void(int y0, int y1, int width)> pixels_final;
};

// What a frame is traced with: the objects as the tracers take them, every object's tracer and
// the Embree scene over them. The scene must outlive it (shading reads its materials). Only a
// transparent material starts rays inside a solid (transparency.h): without one, a scene that
// the direct paths trace builds no Embree scene (EmbreeScene's `interiors`).
struct TracedScene {
  TracedScene(const Scene& scene, LipschitzMode mode)
      : objects(traced_objects(scene)), tracers(objects, mode), embree(tracers, scene.transparent) {
    start_threads();  // the frame's workers, beside what the caller does before the frame
  }
  std::vector<TracedObject> objects;
  SceneTracers tracers;
  EmbreeScene embree;
};

struct FrameStats {
  long long primary_rays = 0;
  long long steps = 0;           // all field/interval evaluations, shadow rays included
  long long refined_pixels = 0;  // traced again by adaptive anti-aliasing
  RayWork primary, shadow;
};

// The first pass's parallel tasks over a data window of width x height pixels at (x0, y0) of the
// frame: the tiles it meets. Threads beyond that only cost their start-up.
int frame_tasks(int x0, int y0, int width, int height);

// Renders the film's data window of its full_width x full_height frame at opt.spp (or
// scene.image.spp); never changes the scene. Returns false if cancelled.
bool render_frame(const Scene& scene, const TracedScene& rt, const RenderOptions& opt, Film& film,
                  Progress* progress, FrameStats* stats);

}  // namespace softtrace

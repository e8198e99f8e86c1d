#include "render/frame.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "render/camera.h"
#include "render/cancel.h"
#include "render/shading.h"

namespace softtrace {

namespace {

constexpr int kTile = 16;  // a task's pixels a side
// The smallest beam's pixels a side. A tile is the first beam; each beam certifies the approach to
// every object for all its rays (ObjectTracer::clear_depth), then its quarters go on from there,
// down to this size. Measured on fig000_12b_soft_blend at 640x480, one thread, median frames:
// without beams 0.61 s (1 spp) and 2.38 s (4 spp); smallest beams of 16, 8, 4 and 2 pixels at 4
// spp 1.25, 1.14, 1.01 and 0.99 s; of 4 and 2 pixels at 1 spp 0.27 and 0.28 s.
constexpr int kBeam = 4;
constexpr int kBeamLevels = 3;  // 16, 8, 4
static_assert(kTile == kBeam << (kBeamLevels - 1));

// Sample s of a pixel: s = 0 is the centre (its hit feeds the AOVs); the rest follow the R2
// low-discrepancy sequence, so results need no random state.
void sample_offset(int s, double& dx, double& dy) {
  dx = std::fmod(0.5 + s * 0.7548776662466927, 1.0);
  dy = std::fmod(0.5 + s * 0.5698402909980532, 1.0);
}

struct Work {
  RayWork primary, shadow;
  // Each beam level's certified depth per object ([level * objects + object]).
  std::vector<double> clear;
};

// One frame's pixels, traced beam by beam. Tiles and beams are aligned to the full frame, never
// to the data window, so a pixel's rays start where they would in any crop of the frame.
class FrameTracer {
 public:
  FrameTracer(const Scene& scene, const TracedScene& rt, Film& film, const RenderOptions& opt)
      : scene_(scene),
        rt_(rt),
        film_(film),
        cancel_(opt.cancel),
        spp_(samples_per_pixel(scene.camera, opt.spp ? opt.spp : scene.image.spp)),
        camera_(scene.camera, film.full_width, film.full_height),
        objects_(rt.tracers.size()) {}

  // The full-frame tile at (tx, ty) (in pixels), where it meets the data window.
  void tile(int tx, int ty, Work& work) const {
    work.clear.resize(size_t(kBeamLevels) * objects_);
    beam(tx, ty, 0, nullptr, work);
  }

 private:
  // The pixels [x, x + size) x [y, y + size) of the full frame, size = kTile >> level, from the
  // depths `from` (per object) that the beam holding it certified.
  void beam(int x, int y, int level, const double* from, Work& work) const {
    const int size = kTile >> level;
    if (x >= film_.x0 + film_.width || x + size <= film_.x0 || y >= film_.y0 + film_.height ||
        y + size <= film_.y0 || cancelled())
      return;
    // Rays from a lens or an orthographic plane leave no single eye: no frustum holds them, and
    // each ray approaches the objects on its own.
    if (!camera_.single_eye()) {
      for (int py = std::max(y, film_.y0); py < std::min(y + size, film_.y0 + film_.height); ++py)
        for (int px = std::max(x, film_.x0); px < std::min(x + size, film_.x0 + film_.width); ++px)
          pixel(px, py, nullptr, work);
      return;
    }
    const Frustum fr = camera_.frustum(x, y, std::min(x + size, film_.full_width),
                                       std::min(y + size, film_.full_height));
    double* clear = work.clear.data() + size_t(level) * objects_;
    TraceCounters beam_work;
    for (int o = 0; o < objects_; ++o) {
      const ObjectTracer* tracer = rt_.tracers.tracer(o);  // a primitive's hit costs no approach
      clear[o] = tracer ? tracer->clear_depth(fr, from ? from[o] : 0, beam_work) : 0;
    }
    // The beam's work is the primary rays' (its passes are counted, not its rays).
    work.primary.box_evals += beam_work.box_evals;
    if (level + 1 < kBeamLevels) {
      const int h = size / 2;
      for (int q = 0; q < 4; ++q) beam(x + (q & 1) * h, y + (q >> 1) * h, level + 1, clear, work);
      return;
    }
    const BeamClear certified{fr.forward, clear};
    for (int py = std::max(y, film_.y0); py < std::min(y + size, film_.y0 + film_.height); ++py)
      for (int px = std::max(x, film_.x0); px < std::min(x + size, film_.x0 + film_.width); ++px)
        pixel(px, py, &certified, work);
  }

  // A tile of a slow field (a blend of thousands of children at many samples) takes minutes:
  // a cancel is noticed before every sample (and, in shade(), every light and secondary ray), so
  // it acts within one ray's time. The pixels left are garbage, but a cancelled frame is never
  // written.
  bool cancelled() const { return cancel_requested(cancel_); }

  // The full-frame pixel (x, y), inside the data window.
  // `certified`: what the pixel's beam certified (none for a camera without a single eye).
  void pixel(int x, int y, const BeamClear* certified, Work& work) const {
    const size_t i = size_t(y - film_.y0) * film_.width + (x - film_.x0);
    const int spp = spp_;
    Vec3 sum{0, 0, 0};
    int covered = 0;
    for (int s = 0; s < spp; ++s) {
      // A relaxed load per sample costs nothing beside tracing it; the frame is thrown away.
      if (cancelled()) return;
      double dx, dy;
      sample_offset(s, dx, dy);
      double lx, ly;
      lens_sample(x, y, s, spp, lx, ly);
      const Ray ray = camera_.generate(x + dx, y + dy, lx, ly);
      const TraceHit hit =
          rt_.embree.intersect(ray, 0, std::numeric_limits<double>::infinity(), certified);
      work.primary.add(hit.work);
      RayWork shadow;
      Vec3 normal{0, 0, 0}, albedo{0, 0, 0};  // the background's
      if (hit.hit) {
        const Shaded sh = shade(scene_, rt_.tracers, rt_.embree, ray, hit, shadow, cancel_);
        sum += sh.color;
        ++covered;
        normal = sh.normal;
        albedo = sh.albedo;
      }
      if (s == 0) aovs(i, hit, normal, albedo, shadow);
      work.shadow += shadow;
    }
    for (int k = 0; k < 3; ++k) film_.rgba[i * 4 + k] = static_cast<float>(sum[k] / spp);
    film_.rgba[i * 4 + 3] = static_cast<float>(covered) / spp;
  }

  // The pixel-centre ray's AOVs, into the planes the film has. The background adds nothing to
  // rgba (premultiplied); its depth is +inf.
  void aovs(size_t i, const TraceHit& hit, const Vec3& normal, const Vec3& albedo,
            const RayWork& shadow) const {
    if (!film_.depth.empty())
      film_.depth[i] = hit.hit ? static_cast<float>(hit.t) : std::numeric_limits<float>::infinity();
    if (!film_.normal.empty())
      for (int k = 0; k < 3; ++k) film_.normal[i * 3 + k] = static_cast<float>(normal[k]);
    if (!film_.steps.empty())
      film_.steps[i] = static_cast<float>(hit.work.evaluations() + shadow.evaluations());
    if (!film_.albedo.empty())
      for (int k = 0; k < 3; ++k) film_.albedo[i * 3 + k] = static_cast<float>(albedo[k]);
  }

  const Scene& scene_;
  const TracedScene& rt_;
  Film& film_;
  const std::atomic<bool>* cancel_;
  const int spp_;
  const ViewCamera camera_;
  const int objects_;
};

}  // namespace

bool render_frame(const Scene& scene, const TracedScene& rt, const RenderOptions& opt, Film& film,
                  Progress* progress, FrameStats* stats) {
  const FrameTracer tracer(scene, rt, film, opt);
  // The full frame's tiles that meet the data window [x0, x0 + width) x [y0, y0 + height).
  const int x1 = film.x0 + film.width, y1 = film.y0 + film.height;
  const int gx0 = film.x0 / kTile, gy0 = film.y0 / kTile;
  const int tiles_x = (x1 + kTile - 1) / kTile - gx0, tiles_y = (y1 + kTile - 1) / kTile - gy0;
  tbb::combinable<Work> work_total;

  // One tile per task; a cancel is noticed before the next sample (FrameTracer::pixel).
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
      [&](const tbb::blocked_range<int>& tiles) {
        Work& work = work_total.local();
        for (int t = tiles.begin(); t < tiles.end(); ++t) {
          if (opt.cancel && *opt.cancel) return;
          const int tx = (gx0 + t % tiles_x) * kTile, ty = (gy0 + t / tiles_x) * kTile;
          tracer.tile(tx, ty, work);
          if (progress) {
            const int w = std::min(tx + kTile, x1) - std::max(tx, film.x0);
            const int h = std::min(ty + kTile, y1) - std::max(ty, film.y0);
            progress->advance(long(w) * h);
          }
        }
      },
      tbb::simple_partitioner());

  if (stats) {
    *stats = FrameStats{};
    stats->primary_rays = static_cast<long long>(film.width) * film.height *
                          samples_per_pixel(scene.camera, opt.spp ? opt.spp : scene.image.spp);
    work_total.combine_each([&](const Work& w) {
      stats->primary += w.primary;
      stats->shadow += w.shadow;
    });
    stats->steps = stats->primary.evaluations() + stats->shadow.evaluations();
  }
  return !(opt.cancel && *opt.cancel);
}

}  // namespace softtrace

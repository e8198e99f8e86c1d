#include "frame.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "camera.h"
#include "shading.h"

namespace softtrace {

namespace {

constexpr int kTile = 16;

// Sample s of a pixel: s = 0 is the centre (its hit feeds the AOVs); the rest follow the R2
// low-discrepancy sequence, so results need no random state.
void sample_offset(int s, double& dx, double& dy) {
  dx = std::fmod(0.5 + s * 0.7548776662466927, 1.0);
  dy = std::fmod(0.5 + s * 0.5698402909980532, 1.0);
}

}  // namespace

bool render_frame(const Scene& scene, const TracedScene& rt, const RenderOptions& opt, Film& film,
                  Progress* progress, FrameStats* stats) {
  const int W = film.width, H = film.height, spp = scene.image.spp;
  const PinholeCamera camera(scene.camera, film.full_width, film.full_height);
  const int tiles_x = (W + kTile - 1) / kTile, tiles_y = (H + kTile - 1) / kTile;
  struct Work {
    RayWork primary, shadow;
  };
  tbb::combinable<Work> work_total;

  // One tile per task: a tile is a few hundred pixels at most, so a cancel is noticed soon
  // whatever the image's width.
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tiles_x * tiles_y, 1),
      [&](const tbb::blocked_range<int>& tiles) {
        Work& work = work_total.local();
        for (int t = tiles.begin(); t < tiles.end(); ++t) {
          if (opt.cancel && *opt.cancel) return;
          const int tx = t % tiles_x * kTile, ty = t / tiles_x * kTile;
          const int tw = std::min(kTile, W - tx), th = std::min(kTile, H - ty);
          for (int y = ty; y < ty + th; ++y) {
            for (int x = tx; x < tx + tw; ++x) {
              const size_t i = size_t(y) * W + x;
              // The ray comes from the pixel's place in the full frame.
              const double fx = film.x0 + x, fy = film.y0 + y;
              Vec3 sum{0, 0, 0};
              int covered = 0;
              for (int s = 0; s < spp; ++s) {
                double dx, dy;
                sample_offset(s, dx, dy);
                const Ray ray = camera.generate(fx + dx, fy + dy);
                const TraceHit hit =
                    rt.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
                work.primary.add(hit.work);
                RayWork shadow;
                if (hit.hit) {
                  const Shaded sh = shade(scene, rt.tracers, rt.embree, ray, hit, shadow);
                  sum += sh.color;
                  ++covered;
                  if (s == 0) {
                    film.depth[i] = static_cast<float>(hit.t);
                    for (int k = 0; k < 3; ++k)
                      film.normal[i * 3 + k] = static_cast<float>(sh.normal[k]);
                  }
                } else if (s == 0) {  // the background adds nothing: film.rgba is premultiplied
                  film.depth[i] = std::numeric_limits<float>::infinity();
                }
                if (s == 0)
                  film.steps[i] = static_cast<float>(hit.work.evaluations() + shadow.evaluations());
                work.shadow += shadow;
              }
              for (int k = 0; k < 3; ++k) film.rgba[i * 4 + k] = static_cast<float>(sum[k] / spp);
              film.rgba[i * 4 + 3] = static_cast<float>(covered) / spp;
            }
          }
          if (progress) progress->advance(long(tw) * th);
        }
      },
      tbb::simple_partitioner());

  if (stats) {
    *stats = FrameStats{};
    stats->primary_rays = static_cast<long long>(W) * H * spp;
    work_total.combine_each([&](const Work& w) {
      stats->primary += w.primary;
      stats->shadow += w.shadow;
    });
    stats->steps = stats->primary.evaluations() + stats->shadow.evaluations();
  }
  return !(opt.cancel && *opt.cancel);
}

}  // namespace softtrace

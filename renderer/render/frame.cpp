#include "render/frame.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <new>
#include <optional>
#include <type_traits>
#include <vector>

#include "render/antialias.h"
#include "render/beam_misses.h"
#include "render/camera.h"
#include "render/cancel.h"
#include "render/plain_floor.h"
#include "render/shading.h"
#include "render/shadow_beams.h"
#include "trace/primitive_trace.h"
#include "trace/unmet_rays.h"

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
// The tile, its quarters and theirs: 1 + 4 + 16 (the sum of 4^level over the levels).
constexpr int kBeamsPerTile = ((1 << (2 * kBeamLevels)) - 1) / 3;
constexpr int kBlocksPerTile = 1 << (2 * (kBeamLevels - 1));  // the smallest beams: 16

// Sample s of a pixel: s = 0 is the centre (its hit feeds the AOVs); the rest follow the R2
// low-discrepancy sequence, so results need no random state.
void sample_offset(int s, double& dx, double& dy) {
  if (s == 0) {  // fmod's value for s = 0, without its call (two were 2 % of a dense cloud's frame)
    dx = dy = 0.5;
    return;
  }
  dx = std::fmod(0.5 + s * 0.7548776662466927, 1.0);
  dy = std::fmod(0.5 + s * 0.5698402909980532, 1.0);
}

// A camera ray traced, waiting for its shading.
struct TracedSample {
  Ray ray;
  TraceHit hit;
};

// A pixel of the tile whose samples are traced: samples[first, first + count) of its Work.
struct TracedPixel {
  int x, y;
  int first, count;
  int block;  // its 4-pixel block in the tile, numbered quarter by quarter (ShadowBeams' levels)
  int point;  // its hit samples' shadow-ray points: Work::points[point, ...), one per hit
};

// A tile's records (its traced samples, pixels, shadow-ray points) in storage kept from tile to
// tile, with their own count: a record is written where it stays. (A vector's emplace_back copied
// each hit's sample, 176 bytes, in an out-of-line call with its growth path: 4 % of the frame's
// own instructions on pov:blob1a.) room(k) gives the place of the next k records, which count
// once `n` is raised past them. The store's size is kept as a count (`held`): from the vector's
// ends it was a division by the record's size (a multiplication and two more instructions) at
// every camera ray's room.
template <class T>
struct TileRecords {
  std::vector<T> store;
  size_t n = 0;
  size_t held = 0;  // store.size()

  T* room(size_t k) {
    if (n + k > held) [[unlikely]]
      grow(n + k);
    return store.data() + n;
  }
  [[gnu::noinline]] void grow(size_t need) {
    store.resize(std::max(need, 2 * store.size()));
    held = store.size();
  }
  size_t size() const { return n; }
  bool empty() const { return n == 0; }
  void clear() { n = 0; }
  T* data() { return store.data(); }
  const T* data() const { return store.data(); }
  T* begin() { return store.data(); }
  T* end() { return store.data() + n; }
  T& operator[](size_t i) { return store[i]; }
  const T& operator[](size_t i) const { return store[i]; }
};

// One thread's own (frame.cpp's run_pass), side by side in one vector: a cache line apiece, so
// that one thread's counters never share a line with the next's (without it, when the tiles
// were handed out one at a time, the 2-thread frames of molecule and meets1 took 5-10 % longer).
struct alignas(64) Work {
  RayWork primary, shadow;
  // Each beam level's certified depth per object ([level * objects + object]).
  std::vector<double> clear;
  // Each beam's blobs per object, for sums of polynomial blobs ([beam * objects + object], the
  // tile's beams numbered as beam() visits them). One slot per beam, not per level: a hit's
  // normal takes its beam's list (TraceHit::blobs) when the tile is shaded, after the tile's
  // other beams are traced.
  std::vector<BlobBeam> blobs;
  int beams = 0;  // the slots of `blobs` this tile has taken
  // The tile's camera rays, traced before any is shaded: their hits place the shadow rays'
  // blocks (ShadowBeams).
  TileRecords<TracedSample> samples;
  TileRecords<TracedPixel> pixels;
  TileRecords<ShadowBeams::Point> points;
  // Where each 4-pixel block's points start, the last block's end after them
  // (FrameTracer::shade_tile): block b's are points[block_starts[b], block_starts[b + 1]).
  int block_starts[kBlocksPerTile + 1];
  ShadowBeams::Lists shadow_lists;
  TraceHit unmet;  // an unmet beam's ray's answer (FrameTracer::camera_hit)
};

// One frame's pixels, traced beam by beam. Tiles and beams are aligned to the full frame, never
// to the data window, so a pixel's rays start where they would in any crop of the frame.
class FrameTracer {
 public:
  // The first pass traces every pixel with its samples; the second traces again those that
  // adaptive anti-aliasing marks (render/antialias.h).
  enum class Pass { First, Refine };

  // `adaptive`: the frame's adaptive anti-aliasing, or null without it.
  FrameTracer(const Scene& scene, const TracedScene& rt, Film& film, const RenderOptions& opt,
              AdaptivePixels* adaptive)
      : scene_(scene),
        rt_(rt),
        film_(film),
        cancel_(opt.cancel),
        spp_(samples_per_pixel(scene.camera, opt.spp ? opt.spp : scene.image.spp)),
        refined_spp_(spp_ * scene.image.antialias.depth * scene.image.antialias.depth),
        camera_(scene.camera, film.full_width, film.full_height),
        objects_(rt.tracers.size()),
        window_{film.x0, film.y0, film.x0 + film.width, film.y0 + film.height},
        adaptive_(adaptive),
        shadow_beams_(scene, rt.tracers),
        floor_(scene, rt.embree),
        plain_(plain_objects(scene, floor_)),
        lifts_(object_lifts(scene)),
        aov_means_(!film.normal.empty() || !film.albedo.empty()),
        aov_planes_(aov_means_ || !film.depth.empty() || !film.steps.empty()),
        misses_(rt.tracers, camera_) {
    // A floor pixel written as it is traced (floor_pixel) needs the tile's points made as it is
    // traced, in ShadowBeams' block order: one sample a pixel, the beams' order (a single eye),
    // one pass, and the floor's lean colours, with lists to build for the other hits.
    const ObjectTracer* field =
        floor_.lean() ? rt.tracers.tracer(rt.embree.floor().field) : nullptr;
    if (field && spp_ == 1 && !adaptive && camera_.single_eye() && shadow_beams_.active())
      floor_pixels_ = floor_.unlisted_rays(field->box(), unlisted_);
    for (size_t k = 0; floor_pixels_ && k < floor_.lean_count(); ++k) {
      Vec3 sum{0, 0, 0};  // pixel()'s sum of its one sample, from 0
      sum += floor_.lean_shaded(int(k)).color;
      floor_rgba_.push_back({static_cast<float>(sum.x), static_cast<float>(sum.y),
                             static_cast<float>(sum.z), 1.0f});  // covered
    }
    for (int o = 0; o < objects_; ++o) {
      const ObjectTracer* tracer = rt.tracers.tracer(o);
      beams_count_ = beams_count_ || (tracer && !tracer->blob_sum());
    }
    if (!camera_.single_eye()) return;
    double dx, dy;
    sample_offset(0, dx, dy);
    columns_.resize(size_t(film.full_width));
    rows_.resize(size_t(film.full_height));
    for (int x = 0; x < film.full_width; ++x)
      columns_[size_t(x)] = camera_.column_part(camera_.column(x + dx));
    for (int y = 0; y < film.full_height; ++y)
      rows_[size_t(y)] = camera_.row_part(camera_.row(y + dy));
  }

  int refined_spp() const { return refined_spp_; }

  // The full-frame tile at (tx, ty) (in pixels), where it meets `area`: the pass's pixels.
  // Its camera rays are all traced first, then shaded block by block (shade_tile).
  void tile(int tx, int ty, const PixelRect& area, Pass pass, Work& work) const {
    work.clear.resize(size_t(kBeamLevels) * objects_);
    work.blobs.resize(size_t(kBeamsPerTile) * objects_);
    work.beams = 0;
    work.samples.clear();
    work.pixels.clear();
    work.points.clear();
    std::fill_n(work.block_starts, kBlocksPerTile + 1, 0);
    beam(tx, ty, 0, nullptr, nullptr, false, area, pass, work);
    if (!work.pixels.empty()) shade_tile(pass, work);  // a background tile has nothing to shade
  }

 private:
  // The pixels [x, x + size) x [y, y + size) of the full frame, size = kTile >> level, from the
  // depths `from` and the blob lists `parent` (per object) of the beam holding it. A beam's place
  // and its certified depths depend only on where it is in the full frame, not on `area`.
  // `background`: the holding beam meets no object's box (BeamMisses), nor then does this one.
  void beam(int x, int y, int level, const double* from, const BlobBeam* parent, bool background,
            const PixelRect& area, Pass pass, Work& work) const {
    const int size = kTile >> level;
    if (x >= area.x1 || x + size <= area.x0 || y >= area.y1 || y + size <= area.y0 || cancelled())
      return;
    if (pass == Pass::Refine && !adaptive_->any({x, y, x + size, y + size})) return;
    // Rays from a lens or an orthographic plane leave no single eye: no frustum holds them, and
    // each ray approaches the objects on its own.
    if (!camera_.single_eye()) {
      for (int py = std::max(y, area.y0); py < std::min(y + size, area.y1); ++py)
        for (int px = std::max(x, area.x0); px < std::min(x + size, area.x1); ++px)
          trace_pixel(px, py, nullptr, pass, work);
      return;
    }
    const int x1 = std::min(x + size, film_.full_width), y1 = std::min(y + size, film_.full_height);
    const Frustum fr = camera_.frustum(x, y, x1, y1);
    background = background || (misses_.ever() && misses_.misses(fr, x, y, x1, y1));
    const PixelRect block{std::max(x, area.x0), std::max(y, area.y0), std::min(x1, area.x1),
                          std::min(y1, area.y1)};
    if (background && !beams_count_) {  // no quarter's beam would count any work either
      background_pixels(block, pass, work);
      return;
    }
    double* clear = work.clear.data() + size_t(level) * objects_;
    TraceCounters beam_work;
    for (int o = 0; o < objects_; ++o) {
      const ObjectTracer* tracer = rt_.tracers.tracer(o);  // a primitive's hit costs no approach
      clear[o] = tracer ? tracer->clear_depth(fr, from ? from[o] : 0, beam_work) : 0;
    }
    // The beam's work is the primary rays' (its passes are counted, not its rays): a background
    // beam's too, so that the counters are those of the frame without the certificate.
    work.primary.box_evals += beam_work.box_evals;
    BlobBeam* blobs = work.blobs.data() + size_t(work.beams++) * objects_;
    for (int o = 0; o < objects_; ++o) {
      const ObjectTracer* tracer = rt_.tracers.tracer(o);
      if (tracer && tracer->blob_sum() && !background)  // no ray of a background beam reads it
        tracer->blob_beam(fr, parent ? parent + o : nullptr, blobs + o, level + 1 == kBeamLevels);
      else
        blobs[o].valid = false;
    }
    if (level + 1 < kBeamLevels) {
      const int h = size / 2;
      for (int q = 0; q < 4; ++q)
        beam(x + (q & 1) * h, y + (q >> 1) * h, level + 1, clear, blobs, background, area, pass,
             work);
      return;
    }
    if (background) {
      background_pixels(block, pass, work);
      return;
    }
    BeamClear certified{fr.forward, clear, blobs};
    certified.unmet = rt_.embree.unmet(certified);
    certified.passable = !certified.unmet && rt_.embree.passable(certified);
    certified.reach = reach_;
    certified.floor_gap = floor_gap_;
    const int px0 = std::max(x, area.x0), px1 = std::min(x + size, area.x1);
    const int py0 = std::max(y, area.y0), py1 = std::min(y + size, area.y1);
    // An unmet or passable block of a lone blob sum, in a first pass of one sample a pixel: its
    // rays answered with what they share taken once (unmet_rays.h), most of a sparse cloud's
    // traced pixels (meets1 at 640x480: 160,532 of 184,896).
    UnmetRays unmet;
    if (pass == Pass::First && spp_ == 1 && rt_.embree.unmet_rays(certified, fr.eye, &unmet)) {
      // A ray unmet does not answer, intersect_unmet and intersect_passing would not either: it is
      // searched without asking them again (passes_listed_balls was 1.2 M instructions twice).
      BeamClear searched = certified;
      searched.unmet = searched.passable = false;
      for (int py = py0; py < py1; ++py)
        for (int px = px0; px < px1; ++px) unmet_pixel(px, py, searched, unmet, work);
      return;
    }
    // The common block, a first pass of one sample a pixel, with both known to the pixels' loop:
    // its tests of the pass and the count go from every pixel.
    if (pass == Pass::First && spp_ == 1) {
      for (int py = py0; py < py1; ++py)
        for (int px = px0; px < px1; ++px) trace_pixel(px, py, &certified, Pass::First, work, 1);
      return;
    }
    for (int py = py0; py < py1; ++py)
      for (int px = px0; px < px1; ++px) trace_pixel(px, py, &certified, pass, work);
  }

  // The camera rays of pixel (x, y) of the pass, traced into work.samples (none where the pass
  // leaves the pixel alone; a pixel cancelled part way is left out, never shaded).
  // `known_spp`: the pass's samples a pixel where the caller knows them (0: not known).
  [[gnu::always_inline]] void trace_pixel(int x, int y, const BeamClear* certified, Pass pass,
                                          Work& work, int known_spp = 0) const {
    if (pass == Pass::Refine && !adaptive_->refine(x, y)) return;
    const int spp = known_spp ? known_spp : pass == Pass::First ? spp_ : refined_spp_;
    const int first = static_cast<int>(work.samples.size());
    // The samples are traced into their places past the tile's others, and counted only where
    // the pixel has a hit: most of a sparse frame's pixels are its background's, whose places
    // the next pixel takes again.
    TracedSample* const sample = work.samples.room(size_t(spp));
    if (spp == 1) {
      if (cancelled()) return;
      sample->ray = camera_ray(x, y, 0, 1);
      // An unmet beam's ray is read where intersect_unmet put it, not copied out (trace_into).
      if (unmet_answers(sample->ray, certified, work))
        one_sample(x, y, first, *sample, &work.unmet, pass, work);
      else
        one_sample(x, y, first, *sample, &trace_into(*sample, certified), pass, work);
      return;
    }
    bool met = false;  // whether any sample has a hit
    for (int s = 0; s < spp; ++s) {
      // A relaxed load per sample costs nothing beside tracing it; the frame is thrown away, and
      // the pixel's samples are left uncounted.
      if (cancelled()) return;
      TracedSample& t = sample[s];
      t.ray = camera_ray(x, y, s, spp);
      if (unmet_answers(t.ray, certified, work))
        t.hit = work.unmet;
      else
        trace_into(t, certified);
      work.primary.add(t.hit.work);
      met = met || t.hit.hit;
    }
    if (met) {
      work.samples.n += size_t(spp);
      *work.pixels.room(1) = traced_pixel(x, y, first, spp);
      ++work.pixels.n;
      return;
    }
    // The background's pixel (94 % of a sparse cloud's frame) is written now, by the code that
    // shades it: its samples have no hit, so no shadow ray and no shadow list (a block's lists
    // are built from its hits alone), and the tile's shading skips it.
    Vec3 sky{0, 0, 0};
    if (scene_.sky)
      for (int s = 0; s < spp; ++s) sky += scene_.sky->seen(sample[s].ray.d);
    miss_pixel(x, y, spp, scene_.sky ? spp : 0, sky, sample[0].hit.work, pass);
  }

  // The pixels `block` of a background beam (background_pixel each). In the first pass without a
  // sky or adaptive anti-aliasing each is miss_pixel's plain background, written a row at a time:
  // colour and alpha 0, normal and albedo 0, Z +inf, steps 0 (the centre ray's evaluations, none).
  void background_pixels(const PixelRect& block, Pass pass, Work& work) const {
    if (pass == Pass::Refine || scene_.sky || adaptive_) {
      for (int py = block.y0; py < block.y1; ++py)
        for (int px = block.x0; px < block.x1; ++px) background_pixel(px, py, pass, work);
      return;
    }
    if (block.empty() || cancelled()) return;
    work.primary.rays += long(block.x1 - block.x0) * (block.y1 - block.y0) * spp_;
    // The film's pixels of the block (all of them: the first pass's area is the data window).
    const int x0 = std::max(block.x0, window_.x0), x1 = std::min(block.x1, window_.x1);
    if (x0 >= x1) return;
    const size_t n = size_t(x1 - x0);
    for (int py = std::max(block.y0, window_.y0); py < std::min(block.y1, window_.y1); ++py) {
      const size_t i = size_t(py - film_.y0) * film_.width + (x0 - film_.x0);
      std::fill_n(&film_.rgba[i * 4], n * 4, 0.0f);
      if (!film_.normal.empty()) std::fill_n(&film_.normal[i * 3], n * 3, 0.0f);
      if (!film_.albedo.empty()) std::fill_n(&film_.albedo[i * 3], n * 3, 0.0f);
      if (!film_.depth.empty())
        std::fill_n(&film_.depth[i], n, std::numeric_limits<float>::infinity());
      if (!film_.steps.empty()) std::fill_n(&film_.steps[i], n, 0.0f);
    }
  }

  // trace_pixel for the first pass's pixel (x, y) of one sample in a block whose rays `unmet`
  // answers: written as one_sample writes a miss, its counters added; a ray it does not answer
  // (one meeting a passable block's balls, mostly) is traced by trace_pixel with `searched`, the
  // block's BeamClear without unmet and passable.
  [[gnu::always_inline]] void unmet_pixel(int x, int y, const BeamClear& searched,
                                          const UnmetRays& unmet, Work& work) const {
    if (cancelled()) return;
    const Ray ray = camera_ray(x, y, 0, 1);
    TraceCounters counters;
    // A pinhole's ray leaves the camera's eye, the block's frustum's, for which `unmet` was made.
    if (!unmet.answer_from_eye(ray, counters)) {
      trace_pixel(x, y, &searched, Pass::First, work, 1);
      return;
    }
    work.primary.add(counters);
    Vec3 sky{0, 0, 0};
    if (scene_.sky) sky += scene_.sky->seen(ray.d);
    miss_pixel(x, y, 1, scene_.sky ? 1 : 0, sky, counters, Pass::First);
  }

  // trace_pixel for a pixel of a background beam (BeamMisses): each of its samples' rays would
  // meet no object's box, so has no hit and no work counted (a ray of RayWork::add with nothing
  // else); its pixel is written as trace_pixel writes such a one, a camera ray made only for a
  // sky, which needs its direction.
  void background_pixel(int x, int y, Pass pass, Work& work) const {
    if (pass == Pass::Refine && !adaptive_->refine(x, y)) return;
    if (cancelled()) return;
    const int spp = pass == Pass::First ? spp_ : refined_spp_;
    work.primary.rays += spp;
    Vec3 sky{0, 0, 0};
    if (scene_.sky)
      for (int s = 0; s < spp; ++s) sky += scene_.sky->seen(camera_ray(x, y, s, spp).d);
    miss_pixel(x, y, spp, scene_.sky ? spp : 0, sky, none_.work, pass);
  }

  // trace_pixel's pixel (x, y) of one sample, traced into `t` (its ray, and its hit unless
  // `hit` is the thread's unmet answer, work.unmet): kept for shading where it has a hit (copied
  // into `t` from work.unmet), else written now (miss_pixel).
  // With floor_pixels_, its hit's shadow-ray point is made now, and a floor pixel whose point needs
  // no list is written now (floor_pixel), with no record.
  [[gnu::always_inline]] void one_sample(int x, int y, int first, TracedSample& t,
                                         const TraceHit* hit, Pass pass, Work& work) const {
    work.primary.add(hit->work);
    if (hit->hit) {
      // A pixel written now takes no record: its place in the tile is made only for the others.
      const int point = static_cast<int>(work.points.size());
      if (floor_pixels_) {
        ShadowBeams::Point& at = *work.points.room(1) = shadow_point(t.ray, *hit);
        // A pixel written now gives its point to no list: the lists are the records' points'
        // (the next point takes its place).
        if (hit->object == floor_.object() && hit->face <= 0 &&
            floor_pixel(x, y, t.ray, *hit, at, work))
          return;
      }
      TracedPixel pixel = traced_pixel(x, y, first, 1);
      if (floor_pixels_) {
        pixel.point = point;
        ++work.points.n;
        work.block_starts[pixel.block + 1] = pixel.point + 1;
      }
      if (hit != &t.hit) t.hit = *hit;
      ++work.samples.n;
      *work.pixels.room(1) = pixel;
      ++work.pixels.n;
      return;
    }
    Vec3 sky{0, 0, 0};
    if (scene_.sky) sky += scene_.sky->seen(t.ray.d);
    miss_pixel(x, y, 1, scene_.sky ? 1 : 0, sky, hit->work, pass);
  }

  // Sample s of spp of pixel (x, y): its camera ray. The lens's point is asked for only where the
  // camera has a lens (generate() ignores it otherwise): its hash and square root cost 30
  // instructions a pixel.
  Ray camera_ray(int x, int y, int s, int spp) const {
    if (s == 0 && !columns_.empty()) return camera_.pinhole(columns_[size_t(x)], rows_[size_t(y)]);
    double dx, dy;
    sample_offset(s, dx, dy);
    double lx = 0, ly = 0;
    if (camera_.lens()) lens_sample(x, y, s, spp, lx, ly);
    return camera_.generate(x + dx, y + dy, lx, ly);
  }

  // The shadow rays' point of a camera hit (ShadowBeams::Point): where shade() lifts them from.
  // A CSG's face's object, as shade() takes it (the call only for a face); an object's own
  // field's or mesh's offset was taken once for the frame (lifts_: no sqrt a point).
  [[gnu::always_inline]] ShadowBeams::Point shadow_point(const Ray& ray,
                                                         const TraceHit& hit) const {
    const Vec3 p = ray.o + ray.d * hit.t;
    const double cone0 = ray.cone_at(hit.t);
    const double lift = hit.face > 0 ? -1 : lifts_[size_t(hit.object)];
    if (lift >= 0) return {p, std::max(lift, cone0)};
    // An object's own that has none (a primitive's, a floor's: own_lift -1) needs no look-up.
    if (hit.face <= 0 && lift < 0) return {p, std::max(unowned_lift(p), cone0)};
    const SceneObject& obj = scene_.objects[size_t(hit.object)];
    return {p, ray_offset(hit.face > 0 ? face_object(obj, hit.face) : obj, p, cone0)};
  }

  // The first pass's pixel (x, y) of one sample, a hit on the floor at its point `at`, written
  // now where none of its shadow rays needs a list (PlainFloor::unlisted_colour): pixel()'s values
  // to the bit (samples()' sums from 0, the centre ray's Z and steps, the means), its colour as
  // the film stores it taken from floor_rgba_. False, nothing written or counted, where one does:
  // it is then shaded with its block's lists. Most of the 1000-blob frame's floor is such pixels,
  // which then take no record, and a tile of them alone no list.
  [[gnu::always_inline]] bool floor_pixel(int x, int y, const Ray& ray, const TraceHit& hit,
                                          const ShadowBeams::Point& at, Work& work) const {
    const int k = floor_.unlisted_colour(ray, at, unlisted_, work.shadow, cancel_);
    if (k < 0) return false;
    const size_t i = size_t(y - film_.y0) * film_.width + (x - film_.x0);  // no apron: no adaptive
    std::memcpy(&film_.rgba[i * 4], floor_rgba_[size_t(k)].data(), sizeof(float) * 4);
    if (aov_planes_) floor_aovs(i, hit, k);
    return true;
  }

  // floor_pixel's AOVs at film index i, its colour's index k. Out of line: inline, its registers
  // cost the frame without a floor's camera rays (beam) some 0.3 M instructions of 1,091 M.
  [[gnu::noinline]] void floor_aovs(size_t i, const TraceHit& hit, int k) const {
    const Shaded sh = floor_.lean_shaded(k);
    SampleMeans means;
    if (aov_means_) {
      means.normal += sh.normal;
      means.albedo += sh.albedo;
    }
    centre_aovs(i, hit, 0);  // its shadow rays evaluate nothing (unlisted_colour)
    mean_aovs(i, means);
  }

  // Whether `ray`, of an unmet beam (BeamClear::unmet) or one of a passable beam that passes
  // between its list's balls (intersect_passing), has its answer (a primitive's hit or none, and
  // its counters) from intersect_unmet in the thread's slot, work.unmet. Filled there in
  // place: a TraceHit returned by value and copied out stalled on intersect_unmet's stores.
  bool unmet_answers(const Ray& ray, const BeamClear* certified, Work& work) const {
    if (!certified) return false;
    if (certified->unmet) return rt_.embree.intersect_unmet(ray, *certified, work.unmet);
    return certified->passable && rt_.embree.intersect_passing(ray, *certified, work.unmet);
  }

  // Sample t's camera ray's nearest hit by intersect, made in t.hit itself (the TraceHit that
  // intersect returns is constructed there, not in a temporary copied in): t.hit.
  const TraceHit& trace_into(TracedSample& t, const BeamClear* certified) const {
    static_assert(std::is_trivially_destructible_v<TraceHit>);
    return *::new (static_cast<void*>(&t.hit)) TraceHit(
        rt_.embree.intersect(t.ray, 0, std::numeric_limits<double>::infinity(), certified));
  }

  // The traced pixel (x, y) whose samples are work.samples[first, first + spp). Full-frame
  // coordinates are not negative: x % kTile / kBeam is a mask and a shift (signed % and / took
  // a dozen instructions more a hit).
  static TracedPixel traced_pixel(int x, int y, int first, int spp) {
    static_assert((kTile & (kTile - 1)) == 0 && kBeam == 4);
    const int bx = (x & (kTile - 1)) >> 2, by = (y & (kTile - 1)) >> 2;
    const int quarter = (by >> 1) * 2 + (bx >> 1), within = (by & 1) * 2 + (bx & 1);
    return {x, y, first, spp, quarter * 4 + within, 0};
  }

  // Shades the tile's traced pixels, a 4-pixel block at a time, with the shadow lists of the
  // tile, its quarter and the block, where ShadowBeams has any.
  void shade_tile(Pass pass, Work& work) const {
    TileRecords<TracedPixel>& pixels = work.pixels;
    // The blocks in ShadowBeams' order: a quarter's four blocks after one another. The beams
    // trace them in that order already; only where they do not is the sort paid for.
    const auto by_block = [](const TracedPixel& a, const TracedPixel& b) {
      return a.block < b.block;
    };
    if (!std::is_sorted(pixels.begin(), pixels.end(), by_block))
      std::stable_sort(pixels.begin(), pixels.end(), by_block);
    const bool lists = shadow_beams_.active();
    int* const block_starts = work.block_starts;
    if (floor_pixels_) {  // its points were made as the tile was traced (one_sample), by block
      for (int b = 0; b < kBlocksPerTile; ++b)  // a block without points ends where it starts
        block_starts[b + 1] = std::max(block_starts[b + 1], block_starts[b]);
    } else if (lists) {
      made_points(work);
    }
    // The pixels of blocks [b0, b1) of 16: from `from` on, where they start.
    const auto end_of = [&](size_t from, int b1) {
      while (from < pixels.size() && pixels[from].block < b1) ++from;
      return from;
    };
    // Each block's lists (and its quarter's and the tile's) are built when its first shadow ray
    // asks for them.
    ShadowListsOnDemand on_demand(shadow_beams_, work.points.data(), block_starts,
                                  work.shadow_lists);
    ShadowListsOnDemand* const by_blocks = lists ? &on_demand : nullptr;
    size_t i = 0;
    for (int b = 0; b < kBlocksPerTile; ++b) {
      const size_t b_end = end_of(i, b + 1);
      if (i == b_end) continue;
      if (lists) on_demand.block(b);
      for (; i < b_end; ++i) pixel(pixels[i], by_blocks, pass, work);
    }
  }

  // The tile's traced pixels' shadow-ray points (one a hit, in the pixels' order) and where each
  // pixel's and each block's start (TracedPixel::point, Work::block_starts).
  void made_points(Work& work) const {
    TileRecords<TracedPixel>& pixels = work.pixels;
    const size_t count = pixels.size();
    ShadowBeams::Point* const points = work.points.room(work.samples.size());
    const TracedSample* const traced = work.samples.data();
    int point = 0;
    int block = 0;  // the blocks before it start at the points before the pixel's
    for (size_t i = 0; i < count; ++i) {
      for (; block <= pixels[i].block; ++block) work.block_starts[block] = point;
      pixels[i].point = point;
      const int first = pixels[i].first, end = first + pixels[i].count;
      for (int s = first; s < end; ++s) {
        const TracedSample& t = traced[s];
        if (t.hit.hit) points[point++] = shadow_point(t.ray, t.hit);
      }
    }
    for (; block <= kBlocksPerTile; ++block) work.block_starts[block] = point;
    work.points.n = size_t(point);
  }

  // A tile of a slow field (a blend of thousands of children at many samples) takes minutes:
  // a cancel is noticed before every sample (and, in shade(), every light and secondary ray), so
  // it acts within one ray's time. The pixels left are garbage, but a cancelled frame is never
  // written.
  bool cancelled() const { return cancel_requested(cancel_); }

  // The full-frame pixel (x, y) of the pass's area. The first pass writes the pixels of the data
  // window (colour and AOVs) and, with adaptive anti-aliasing, tells it every pixel's colour; the
  // second traces a marked pixel again with refined_spp_ samples, which replace its colour. The
  // albedo and normal AOVs are the mean over the samples that made the colour, as a denoiser
  // pairs them with it (an edge pixel's albedo mixes the two sides as its colour does; its normal
  // is then shorter than 1); Z and steps are the pixel-centre ray's (a mean depth across an edge
  // is nobody's depth).
  // `lists`: the shadow lists of the pixel's 4-pixel block (none without ShadowBeams); each hit
  // sets its point in them (samples). Inlined in shade_tile's loop: with samples() built twice,
  // GCC left it out of line, a call a pixel (4.4 M of the floor frame's instructions).
  [[gnu::always_inline]] void pixel(const TracedPixel& tp, ShadowListsOnDemand* lists, Pass pass,
                                    Work& work) const {
    const int x = tp.x, y = tp.y;
    const bool in_film = film_holds(x, y);
    const size_t i = in_film ? size_t(y - film_.y0) * film_.width + (x - film_.x0) : 0;
    switch (pass) {
      case Pass::First: {
        float rgba[4];
        SampleMeans means;
        const bool done = tp.count == 1
                              ? samples<true>(tp, lists, in_film ? &i : nullptr, work, rgba, &means)
                              : samples(tp, lists, in_film ? &i : nullptr, work, rgba, &means);
        if (!done) return;
        if (in_film) {
          std::copy(rgba, rgba + 4, &film_.rgba[i * 4]);
          mean_aovs(i, means);
        }
        if (adaptive_) {
          // Compared as seen: over the plain background (a gradient sky is in rgba already).
          for (int k = 0; k < 3; ++k)
            rgba[k] += static_cast<float>(scene_.background[k]) * (1 - rgba[3]);
          adaptive_->set_first(x, y, rgba);
        }
        return;
      }
      case Pass::Refine: {
        float rgba[4];
        SampleMeans means;
        if (!samples(tp, lists, nullptr, work, rgba, &means)) return;
        std::copy(rgba, rgba + 4, &film_.rgba[i * 4]);
        mean_aovs(i, means);  // Z and steps stay the first pass's pixel-centre ray's
        return;
      }
    }
  }

  // pixel() for pixel (x, y) none of whose `spp` samples has a hit, without samples()' general
  // loop: the same values to the bit. `sky` is the sum of the samples' sky colours in their order
  // (from {0, 0, 0}), `covered` how many it has (all or none); the film's background is added when
  // it is written. The normal and albedo means are 0; Z is +inf and steps the centre ray's own
  // (its counters, `centre`).
  [[gnu::always_inline]] void miss_pixel(int x, int y, int spp, int covered, const Vec3& sky,
                                         const TraceCounters& centre, Pass pass) const {
    float rgba[4] = {0, 0, 0, 0};  // no sky: 0 / spp, each of them +0
    if (covered) {
      for (int k = 0; k < 3; ++k) rgba[k] = static_cast<float>(sky[k] / spp);
      rgba[3] = static_cast<float>(covered) / spp;
    }
    const bool in_film = film_holds(x, y);
    const size_t i = in_film ? size_t(y - film_.y0) * film_.width + (x - film_.x0) : 0;
    const SampleMeans none;  // samples()' 0 / spp
    if (pass == Pass::Refine) {
      std::copy(rgba, rgba + 4, &film_.rgba[i * 4]);
      if (aov_planes_) mean_aovs(i, none);
      return;
    }
    if (in_film) {
      std::copy(rgba, rgba + 4, &film_.rgba[i * 4]);
      if (aov_planes_) {  // a PNG's film has none: four tests a pixel less
        mean_aovs(i, none);
        miss_aovs(i, centre);
      }
    }
    if (adaptive_) {
      for (int k = 0; k < 3; ++k)
        rgba[k] += static_cast<float>(scene_.background[k]) * (1 - rgba[3]);
      adaptive_->set_first(x, y, rgba);
    }
  }

  // Whether the pass's pixel (x, y) is the film's: every pixel a pass visits lies in its area,
  // which is the data window but for the first pass's apron around it with adaptive
  // anti-aliasing (render_frame).
  bool film_holds(int x, int y) const { return !adaptive_ || window_.contains(x, y); }

  // The mean over a pixel's samples of the shaded normal and albedo (0 for a sample that meets
  // nothing, as the background adds nothing to the premultiplied colour).
  struct SampleMeans {
    Vec3 normal{0, 0, 0}, albedo{0, 0, 0};
  };

  // The traced samples of pixel tp shaded into `rgba` (premultiplied); the pixel-centre ray's
  // Z and steps go to the film's pixel `*aov` when given, the samples' means to `*means`. False
  // when cancelled. With `lists`, each hit is shaded with its block's lists and the point
  // ShadowBeams took for it (its shadow rays are then the block's by construction). Inlined in
  // shade_tile's loop: out of line it cost the floor's frame 20 M instructions (60 a sample).
  // `kOne`: the pixel has one sample (tp.count 1), known where the loop is built: the loop's
  // set-up, spilled registers and sums go (callgrind, 1000 blobs at 640x480, every pixel of its
  // floor frame a hit: 9.8 M of the floor frame's 1,385 M, 5.7 M of the cloud frame's 1,159 M).
  template <bool kOne = false>
  [[gnu::always_inline]] bool samples(const TracedPixel& tp, ShadowListsOnDemand* lists,
                                      const size_t* aov, Work& work, float rgba[4],
                                      SampleMeans* means = nullptr) const {
    const int spp = kOne ? 1 : tp.count;
    int point = tp.point;
    Vec3 sum{0, 0, 0};
    SampleMeans sums;
    int covered = 0;
    for (int s = 0; s < spp; ++s) {
      if (cancelled()) return false;
      const Ray& ray = work.samples[size_t(tp.first + s)].ray;
      const TraceHit& hit = work.samples[size_t(tp.first + s)].hit;
      // The shadow rays' work goes to the tile's own sum; the centre ray's steps take what it
      // grew by (integers: exact). A RayWork per sample, zeroed and added in, was 7 words each.
      RayWork& shadow = work.shadow;
      const long long before = shadow.evaluations();
      Vec3 normal{0, 0, 0}, albedo{0, 0, 0};  // the background's
      if (hit.hit) {
        if (lists) lists->at(work.points[size_t(point++)]);
        // A plain object's point (shades_plain, asked once per object for the frame) takes
        // shade()'s short way inline, with its block's lists or, in a scene without them (few
        // blobs: the small real scenes), with its point and offset as shadow_point makes them
        // (shade()'s arithmetic, the object's lift taken once for the frame: no square root a
        // point); the floor's with its lists and the terms PlainFloor took for the frame. The
        // same bits as shade().
        const char way = hit.face <= 0 ? plain_[size_t(hit.object)] : kLongWay;
        const Material& m = scene_.objects[size_t(hit.object)].material;
        const Shaded sh = way == kPlainWay && lists
                              ? shade_plain_hit(scene_, rt_.tracers, rt_.embree, ray, hit, m,
                                                shadow, cancel_, *lists)
                          : way == kPlainWay ? unlisted_plain(ray, hit, m, shadow)
                          : way == kFloorWay && lists
                              ? floor_.shade(scene_, rt_.embree, ray, hit, shadow, cancel_, *lists)
                              : shade(scene_, rt_.tracers, rt_.embree, ray, hit, shadow, cancel_, 1,
                                      1, nullptr, lists);
        sum += sh.color;
        ++covered;
        normal = sh.normal;
        albedo = sh.albedo;
      } else if (scene_.sky) {
        sum += scene_.sky->seen(ray.d);  // opaque: a gradient sky is part of the picture
        ++covered;
      }
      if (s == 0 && aov) centre_aovs(*aov, hit, shadow.evaluations() - before);
      if (aov_means_) {
        sums.normal += normal;
        sums.albedo += albedo;
      }
    }
    if (spp == 1) {  // x / 1 is x to the bit: one sample's pixel takes no divisions
      if (means) *means = sums;
      for (int k = 0; k < 3; ++k) rgba[k] = static_cast<float>(sum[k]);
      rgba[3] = static_cast<float>(covered);
      return true;
    }
    if (means) *means = {sums.normal / spp, sums.albedo / spp};
    for (int k = 0; k < 3; ++k) rgba[k] = static_cast<float>(sum[k] / spp);
    rgba[3] = static_cast<float>(covered) / spp;
    return true;
  }

  // shade() of a plain object's camera hit (face <= 0) in a frame without shadow lists.
  [[gnu::always_inline]] Shaded unlisted_plain(const Ray& ray, const TraceHit& hit,
                                               const Material& m, RayWork& shadow) const {
    const ShadowBeams::Point at = shadow_point(ray, hit);
    return shade_plain_at(scene_, rt_.tracers, rt_.embree, ray, hit, m, at.p, at.margin, shadow,
                          cancel_, nullptr);
  }

  // The pixel-centre ray's Z and steps, into the planes the film has. The background's depth is
  // +inf.
  // `shadow_evaluations`: those of its shadow rays.
  void centre_aovs(size_t i, const TraceHit& hit, long long shadow_evaluations) const {
    if (!film_.depth.empty())
      film_.depth[i] = hit.hit ? static_cast<float>(hit.t) : std::numeric_limits<float>::infinity();
    if (!film_.steps.empty())
      film_.steps[i] = static_cast<float>(hit.work.evaluations() + shadow_evaluations);
  }
  // centre_aovs for a centre ray without a hit (nor shadow rays), from its counters.
  void miss_aovs(size_t i, const TraceCounters& centre) const {
    if (!film_.depth.empty()) film_.depth[i] = std::numeric_limits<float>::infinity();
    if (!film_.steps.empty()) film_.steps[i] = static_cast<float>(centre.evaluations());
  }

  // The samples' mean normal and albedo, into the planes the film has.
  void mean_aovs(size_t i, const SampleMeans& means) const {
    for (int k = 0; k < 3 && !film_.normal.empty(); ++k)
      film_.normal[i * 3 + k] = static_cast<float>(means.normal[k]);
    for (int k = 0; k < 3 && !film_.albedo.empty(); ++k)
      film_.albedo[i * 3 + k] = static_cast<float>(means.albedo[k]);
  }

  static std::vector<double> object_lifts(const Scene& scene) {
    std::vector<double> lifts(scene.objects.size());
    for (size_t o = 0; o < lifts.size(); ++o) lifts[o] = own_lift(scene.objects[o]);
    return lifts;
  }
  // How a point of each object is shaded: shade(), shade_plain_hit (shade_plain_at without
  // lists) or PlainFloor (the floor).
  static constexpr char kLongWay = 0, kPlainWay = 1, kFloorWay = 2;
  static std::vector<char> plain_objects(const Scene& scene, const PlainFloor& floor) {
    std::vector<char> plain(scene.objects.size());
    for (size_t o = 0; o < plain.size(); ++o)
      plain[o] = !shades_plain(scene, scene.objects[o]) ? kLongWay
                 : int(o) == floor.object()             ? kFloorWay
                                                        : kPlainWay;
    return plain;
  }

  const Scene& scene_;
  const TracedScene& rt_;
  Film& film_;
  const std::atomic<bool>* cancel_;
  const int spp_, refined_spp_;
  const ViewCamera camera_;
  // A pinhole perspective camera's ray directions' parts of sample 0 (the pixel's centre) per
  // full-frame column and row (ViewCamera::column_part, row_part of its column, row), or none: a
  // camera ray's two divisions, six products and three sums.
  std::vector<Vec3> columns_, rows_;
  const int objects_;
  const PixelRect window_;  // the film's data window
  AdaptivePixels* const adaptive_;
  const ShadowBeams shadow_beams_;
  // The floor's plain points' terms, or none (object() -1).
  const PlainFloor floor_;
  // Per scene object, whether its points are shaded the short way (shades_plain; a CSG's faces
  // are asked per point, by shade()), and whether it is the floor's (kFloorWay).
  const std::vector<char> plain_;

  // Per scene object, its own_lift (shading.h): the offset's first term where it is the object's
  // alone, else -1.
  const std::vector<double> lifts_;
  // Whether the film has a normal or an albedo plane: without, a sample's shaded normal and
  // albedo are not summed (mean_aovs would write them nowhere).
  const bool aov_means_;
  // Whether the film has any AOV plane (normal, albedo, Z, steps).
  const bool aov_planes_;
  const BeamMisses misses_;
  // Whether a beam's approach may count work (ObjectTracer::clear_depth: a field that is no blob
  // sum): a background beam's quarters are then still visited, for the same counters.
  bool beams_count_ = false;
  // Whether a floor pixel may be written as it is traced (floor_pixel): its shadow rays that
  // miss the floor's field's box need no list, and unlisted_ holds what they ask of the box.
  bool floor_pixels_ = false;
  PlainFloor::UnlistedRays unlisted_;
  // With floor_pixels_, per colour of the floor's lean colours (PlainFloor::lean_shaded), a
  // floor pixel's RGBA as the film stores it: pixel()'s one-sample sum, converted, and covered.
  std::vector<std::array<float, 4>> floor_rgba_;
  // BeamClear::reach of the camera's rays (single_eye(): pinhole rays from its eye).
  const double reach_ = camera_.single_eye() ? BeamClear::reach_from(camera_.eye()) : -1;
  // BeamClear::floor_gap of the camera's rays (single_eye()), or NaN.
  const double floor_gap_ = camera_.single_eye() && rt_.embree.floor().plane
                                ? unplaced_plane_gap(*rt_.embree.floor().plane, camera_.eye())
                                : std::numeric_limits<double>::quiet_NaN();
  const TraceHit none_;  // a background pixel's centre ray's answer: no hit, no work
};

// The full-frame tiles that meet `area`: the first one's grid position and how many a side.
struct TileGrid {
  explicit TileGrid(const PixelRect& area)
      : gx0(area.x0 / kTile),
        gy0(area.y0 / kTile),
        tiles_x((area.x1 + kTile - 1) / kTile - gx0),
        tiles_y((area.y1 + kTile - 1) / kTile - gy0) {}
  int count() const { return tiles_x * tiles_y; }
  const int gx0, gy0, tiles_x, tiles_y;
};

// Runs `pass` over the full-frame tiles that meet `area`, one tile per task; a cancel is noticed
// before the next sample (FrameTracer::samples). Progress counts in first-pass pixels: the data
// window's pixels, then, with `refined`, each pixel traced again as `weight` of them (its share of
// the samples). The frame's `last` pass tells opt.pixels_final of each tile's pixels.
void run_pass(const FrameTracer& tracer, const PixelRect& area, FrameTracer::Pass pass, bool last,
              const PixelRect& window, const RenderOptions& opt, Progress* progress,
              const AdaptivePixels* refined, long weight, std::vector<Work>& work_total) {
  const TileGrid grid(area);
  parallel_each_thread(
      size_t(grid.count()), int(work_total.size()), [&](size_t t, int thread) {  // threads.h
        if (opt.cancel && *opt.cancel) return;
        const int tx = (grid.gx0 + int(t) % grid.tiles_x) * kTile;
        const int ty = (grid.gy0 + int(t) / grid.tiles_x) * kTile;
        const PixelRect seen{std::max(tx, window.x0), std::max(ty, window.y0),
                             std::min(tx + kTile, window.x1), std::min(ty + kTile, window.y1)};
        {
          const FloatingPointMode mode(FloatingPointMode::frames());
          tracer.tile(tx, ty, area, pass, work_total[size_t(thread)]);
          if (progress) {
            const long units = seen.empty() ? 0
                               : refined    ? long(refined->count(seen)) * weight
                                            : long(seen.x1 - seen.x0) * (seen.y1 - seen.y0);
            if (units > 0) progress->advance(units);
          }
        }
        if (last && opt.pixels_final && !seen.empty() && !(opt.cancel && *opt.cancel))
          opt.pixels_final(seen.y0 - window.y0, seen.y1 - window.y0, seen.x1 - seen.x0);
      });
}

}  // namespace

int frame_tasks(int x0, int y0, int width, int height) {
  return TileGrid({x0, y0, x0 + width, y0 + height}).count();
}

bool render_frame(const Scene& scene, const TracedScene& rt, const RenderOptions& opt, Film& film,
                  Progress* progress, FrameStats* stats) {
  const PixelRect window{film.x0, film.y0, film.x0 + film.width, film.y0 + film.height};
  std::optional<AdaptivePixels> adaptive;
  if (scene.image.antialias.on())
    adaptive.emplace(scene.image.antialias, window, film.full_width, film.full_height);
  const FrameTracer tracer(scene, rt, film, opt, adaptive ? &*adaptive : nullptr);
  // Each thread's own, summed at the end: counts, so the totals are the same for any thread count.
  std::vector<Work> work_total(static_cast<size_t>(loop_threads()));
  run_pass(tracer, adaptive ? adaptive->apron() : window, FrameTracer::Pass::First, !adaptive,
           window, opt, progress, nullptr, 0, work_total);
  if (adaptive && !(opt.cancel && *opt.cancel)) {
    adaptive->decide();
    // A pixel traced again costs depth^2 first-pass pixels' samples; the time left counts them
    // from now on.
    const long weight = long(scene.image.antialias.depth) * scene.image.antialias.depth;
    if (progress) progress->add_total(long(adaptive->refined()) * weight);
    run_pass(tracer, window, FrameTracer::Pass::Refine, true, window, opt, progress, &*adaptive,
             weight, work_total);
  }

  if (stats) {
    *stats = FrameStats{};
    stats->primary_rays = static_cast<long long>(film.width) * film.height *
                          samples_per_pixel(scene.camera, opt.spp ? opt.spp : scene.image.spp);
    if (adaptive) {
      stats->refined_pixels = adaptive->refined();
      stats->primary_rays += stats->refined_pixels * tracer.refined_spp();
    }
    for (const Work& w : work_total) {
      stats->primary += w.primary;
      stats->shadow += w.shadow;
    }
    stats->steps = stats->primary.evaluations() + stats->shadow.evaluations();
  }
  return !(opt.cancel && *opt.cancel);
}

}  // namespace softtrace

#include "render/shadow_beams.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace softtrace {

ShadowBeams::ShadowBeams(const Scene& scene, const SceneTracers& tracers)
    : tracers_(tracers), objects_(tracers.size()), slot_(scene.lights.size(), -1) {
  for (int o = 0; o < objects_; ++o)
    if (const ObjectTracer* t = tracers.tracer(o); t && t->blob_count() > kFewBlobs)
      blob_objects_.push_back(o);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (!l.shadows || l.has_area || l.type == Light::Type::Ambient) continue;
    Axes a;
    a.point = l.type != Light::Type::Directional;
    a.position = l.position;
    // A pyramid's apex must be off the origin: its lists hold rays from within 1e3 times its
    // largest coordinate (BlobBeam::holds_toward).
    if (a.point && !(max_abs(l.position) > 0)) continue;
    if (!a.point) a = axes(-l.direction, false, l.position);  // light_arrival's to_light
    slot_[i] = static_cast<int>(lights_.size());
    lights_.push_back(a);
  }
}

ShadowBeams::Axes ShadowBeams::axes(const Vec3& along, bool point, const Vec3& position) {
  Axes a;
  a.along = along;
  a.point = point;
  a.position = position;
  // u across the axis least aligned with `along`, v completing the frame.
  const Vec3 e =
      std::abs(a.along.x) <= std::abs(a.along.y) && std::abs(a.along.x) <= std::abs(a.along.z)
          ? Vec3{1, 0, 0}
      : std::abs(a.along.y) <= std::abs(a.along.z) ? Vec3{0, 1, 0}
                                                   : Vec3{0, 0, 1};
  a.u = cross(a.along, e);
  a.u = a.u / length(a.u);
  a.v = cross(a.along, a.u);
  a.v = a.v / length(a.v);
  return a;
}

void ShadowBeams::build(int level, const Point* points, int begin, int end, Lists& lists) const {
  lists.level[level].resize(lights_.size() * size_t(objects_));
  if (level == 0) {
    if (end > begin) lists.origin = points[begin].p;
    lists.points = end;
    lists.balls.resize(lights_.size() * size_t(end));
    lists.boxes.resize(lights_.size() * size_t(objects_));
    lists.pyramids.resize(lights_.size());
    lists.slopes.resize(lights_.size() * size_t(end));
    lists.lent.resize(lights_.size() * size_t(objects_));
    // The blocks' level takes the lists the tile or a quarter lends (shut_and_lend).
    lists.level[kLevels - 1].resize(lights_.size() * size_t(objects_));
  }
  for (size_t k = 0; k < lights_.size(); ++k)
    if (lights_[k].point)
      build_pyramid(level, lights_[k], k, points, begin, end, lists);
    else
      build_prism(level, lights_[k], k, points, begin, end, lists);
}

void ShadowBeams::build_prism(int level, const Axes& a, size_t k, const Point* points, int begin,
                              int end, Lists& lists) const {
  std::vector<BlobBeam>& out = lists.level[level];
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Extent* balls = lists.balls.data() + k * size_t(lists.points);
  Extent* boxes = lists.boxes.data() + k * size_t(objects_);
  // A shut list lent to the blocks (shut_and_lend): the tile's for the rest of the tile, a
  // quarter's for its blocks. The others' are their own.
  char* const lent = lists.lent.data() + k * size_t(objects_);
  if (level == 0)
    for (const int o : blob_objects_) lent[o] = kOwn;
  const auto own = [&](int o) {
    if (level == 1 && lent[o] == kQuarter) lent[o] = kOwn;
    return lent[o] == kOwn;
  };
  // A quarter's or a block's prism lies in its parent's: where the parent's misses every object's
  // box (most of a floor's tiles beside a cloud), so does its own, and its prism is not needed.
  if (level > 0) {
    bool clear = true, any = false;
    for (const int o : blob_objects_)
      if (own(o)) any = true, clear = clear && lists.level[level - 1][k * objects_ + o].clear;
    if (!any) return;
    if (clear) {
      for (const int o : blob_objects_) {
        if (lent[o] != kOwn) continue;
        BlobBeam& list = out[k * objects_ + o];
        list.valid = false;
        list.shut = false;
        list.clear = end > begin;
      }
      return;
    }
  }
  // The prism's rectangle and depth, in locals (the loops then keep them in registers).
  double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf, z0 = kInf, z1 = -kInf;
  if (level == 0 && end > begin) {
    // The objects' boxes and the tile's points on its axes, once for all its prisms.
    for (const int o : blob_objects_) {
      const Box& box = tracers_.object(o).bounds;
      Extent e{kInf, -kInf, kInf, -kInf, -kInf};
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner{c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                          c & 4 ? box.hi.z : box.lo.z};
        const Vec3 q = corner - lists.origin;
        const double x = dot(q, a.u), y = dot(q, a.v), z = dot(q, a.along);
        e.x0 = std::min(e.x0, x), e.x1 = std::max(e.x1, x);
        e.y0 = std::min(e.y0, y), e.y1 = std::max(e.y1, y);
        e.z = std::max(e.z, z);
      }
      boxes[o] = e;
    }
    if (misses_boxes(a, points, begin, end, lists.origin, boxes)) {
      for (const int o : blob_objects_) {
        BlobBeam& list = out[k * objects_ + o];
        list.valid = list.shut = false;
        list.clear = true;
      }
      return;
    }
    for (int i = begin; i < end; ++i) {
      // The origin lies within the margin of p (grown by 1e-9: the lift's rounding).
      const Vec3 q = points[i].p - lists.origin;
      const double m = points[i].margin * (1 + 1e-9);
      const double x = dot(q, a.u), y = dot(q, a.v), z = dot(q, a.along);
      const Extent b{x - m, x + m, y - m, y + m, z - m};
      balls[i] = b;
      x0 = std::min(x0, b.x0), x1 = std::max(x1, b.x1);
      y0 = std::min(y0, b.y0), y1 = std::max(y1, b.y1);
      z0 = std::min(z0, b.z);
      z1 = std::max(z1, b.z + (b.x1 - b.x0));
    }
  } else {
    for (int i = begin; i < end; ++i) {
      const Extent& b = balls[i];
      x0 = std::min(x0, b.x0), x1 = std::max(x1, b.x1);
      y0 = std::min(y0, b.y0), y1 = std::max(y1, b.y1);
      z0 = std::min(z0, b.z);
      // A block's rays start at most at its balls' tops (z - m + 2 m, rounded): a bound its shut
      // rays check for themselves (BlobBeam::shut), so any rounding of it is safe.
      z1 = std::max(z1, b.z + (b.x1 - b.x0));
    }
  }
  const ShadowPrism prism{lists.origin, a.along, a.u, a.v, x0, x1, y0, y1, z0, z1};
  for (const int o : blob_objects_) {
    if (level > 0 && lent[o] != kOwn) continue;
    BlobBeam& list = out[k * objects_ + o];
    list.valid = false;
    list.clear = false;
    list.shut = false;
    if (end == begin) continue;
    // A prism that misses the object's box sends it no ray: no list, and no walk to build one.
    // Its rays meet no blob: they need no trace at all (BlobBeam::clear).
    const Box& box = tracers_.object(o).bounds;
    const Extent& e = boxes[o];
    const double slack = 1e-9 * (max_abs(box.lo) + max_abs(box.hi) + max_abs(lists.origin));
    if (e.x0 > prism.x1 + slack || e.x1 < prism.x0 - slack || e.y0 > prism.y1 + slack ||
        e.y1 < prism.y0 - slack || e.z < prism.z0 - slack) {
      list.clear = true;
      continue;
    }
    const BlobBeam* parent = level > 0 ? &lists.level[level - 1][k * objects_ + o] : nullptr;
    tracers_[o].shadow_beam(prism, parent, &list);
    // A list with no blob is clear as well: no blob's support reaches into the prism (the list
    // keeps every blob whose bounding sphere does, with its slack), so the field is zero along
    // every ray of the block, which meets no solid (an empty list's walk answers the same after
    // one stretch, counted in the steps AOV; a clear ray counts none). Its quarters' and blocks'
    // are then clear with no prism (above). The floor's blocks inside the box's shadow but outside
    // every blob's are (1000 blobs at 640x480: the rays of 3,251 of the 41,689 floor points whose
    // rays entered the box).
    if (list.valid && list.entries.empty()) {
      list.valid = false;
      list.clear = true;
      continue;
    }
    // The blocks' lists, which their rays take, pick the blobs that may decide them alone; a
    // tile's or a quarter's that one of them shuts is its blocks' list.
    if (level == kLevels - 1)
      tracers_[o].shadow_blockers(&list);
    else
      shut_and_lend(level, k, o, z1, lists);
  }
}

// Whether the tile's prism misses every object's box as build_prism's own test would find it,
// told from the box that bounds the tile's points in world space, without their balls: a floor's
// tile beside the cloud's shadow paid three dot products a point (the 1000-blob frame with a
// floor: 436 such tiles, 111,000 points; build_prism fell by 6.6 M instructions, this took 1.3 M).
// The box of the points (lo, hi) and their largest margin m on an axis w lie within dot(c, w) -+
// (|w.x| h.x + |w.y| h.y + |w.z| h.z) -+ m, c and h its centre (from the origin) and half-size,
// which bounds each point's ball as the loop would compute it; `pad` (1e-10 of the magnitudes)
// covers the rounding of both sides, a few ulps of them. Asked only where the tile's first point
// (the axes' origin, so at 0) lies outside every box's rectangle or beyond its depth: a tile on
// the cloud, or in its shadow, pays one comparison.
bool ShadowBeams::misses_boxes(const Axes& a, const Point* points, int begin, int end,
                               const Vec3& origin, const Extent* boxes) const {
  for (const int o : blob_objects_) {
    const Extent& e = boxes[o];
    if (!(e.x0 > 0 || e.x1 < 0 || e.y0 > 0 || e.y1 < 0 || e.z < 0)) return false;
  }
  // The least and greatest x, y, z and margin (a Point's four doubles in order): with SSE2, two
  // to a register, 9 instructions a point against 25 for the scalar loop. A bound needs no
  // particular order of the comparisons.
  static_assert(sizeof(Point) == 4 * sizeof(double) &&
                offsetof(Point, margin) == 3 * sizeof(double));
  double low[4], high[4];
#ifdef __SSE2__
  const double* const first = &points[begin].p.x;
  __m128d lo_xy = _mm_loadu_pd(first), hi_xy = lo_xy, lo_zm = _mm_loadu_pd(first + 2),
          hi_zm = lo_zm;
  for (int i = begin + 1; i < end; ++i) {
    const double* const p = &points[i].p.x;
    const __m128d xy = _mm_loadu_pd(p), zm = _mm_loadu_pd(p + 2);
    lo_xy = _mm_min_pd(lo_xy, xy), hi_xy = _mm_max_pd(hi_xy, xy);
    lo_zm = _mm_min_pd(lo_zm, zm), hi_zm = _mm_max_pd(hi_zm, zm);
  }
  _mm_storeu_pd(low, lo_xy), _mm_storeu_pd(low + 2, lo_zm);
  _mm_storeu_pd(high, hi_xy), _mm_storeu_pd(high + 2, hi_zm);
#else
  std::memcpy(low, &points[begin], sizeof low), std::memcpy(high, &points[begin], sizeof high);
  for (int i = begin + 1; i < end; ++i) {
    double p[4];
    std::memcpy(p, &points[i], sizeof p);
    for (int c = 0; c < 4; ++c) low[c] = std::min(low[c], p[c]), high[c] = std::max(high[c], p[c]);
  }
#endif
  const double m = high[3] * (1 + 1e-9);
  const Vec3 lo{low[0], low[1], low[2]}, hi{high[0], high[1], high[2]};
  const Vec3 c = (lo + hi) * 0.5 - origin, h = (hi - lo) * 0.5;
  const auto half = [&](const Vec3& w) {
    return std::abs(w.x) * h.x + std::abs(w.y) * h.y + std::abs(w.z) * h.z + m;
  };
  const double cx = dot(c, a.u), cy = dot(c, a.v), cz = dot(c, a.along);
  const double hx = half(a.u), hy = half(a.v), hz = half(a.along);
  const double pad = 1e-10 * (max_abs(lo) + max_abs(hi) + max_abs(origin) + m);
  for (const int o : blob_objects_) {
    const Box& box = tracers_.object(o).bounds;
    const Extent& e = boxes[o];
    const double slack = 1e-9 * (max_abs(box.lo) + max_abs(box.hi) + max_abs(origin)) + pad;
    if (!(e.x0 > cx + hx + slack || e.x1 < cx - hx - slack || e.y0 > cy + hy + slack ||
          e.y1 < cy - hy - slack || e.z < cz - hz - slack))
      return false;
  }
  return true;
}

// A block's shadow rays may take its tile's or its quarter's list instead of its own: that prism
// holds them (its rectangle and depths bound the balls about the block's points, where the rays
// start, as the block's do), and its list holds every blob a ray of it may meet. Where one of its
// blockers shuts it (shut_by's certificate over its rectangle and depths, to z1 the top of all its
// points' balls), each ray of the block whose footprints the certificate covers (shut_decides) is
// answered as any shut list answers it: a hit, one point (first_hit_blobs), the block's own list's
// answer and work where that was shut too. A ray it does not cover takes blocked_by and the
// stretches with the larger list, whose answer is the walk's as with the block's own (its work
// may differ: none did at 640x480 under the 1000-blob cloud). The list moves into the blocks'
// level (swapped: what is left in its place is no list, neither clear nor shut, until that level
// is built again), and the blocks below it build none of their own: no filter, no blockers, no
// prism. Under the 1000-blob cloud at 640x480, 447 of the floor's 599 quarters with lists and 56
// of its 181 tiles can be shut so.
void ShadowBeams::shut_and_lend(int level, size_t k, int o, double z1, Lists& lists) const {
  const size_t i = k * objects_ + o;
  BlobBeam& list = lists.level[level][i];
  if (!list.valid) return;
  list.prism.z1 = z1;
  tracers_[o].shadow_blockers(&list);
  if (!list.shut) return;
  std::swap(list, lists.level[kLevels - 1][i]);
  list.valid = list.clear = list.shut = false;
  lists.lent[i] = level == 0 ? kTile : kQuarter;
}

// The pyramid from the light through the balls about the block's points (where the rays start),
// on the tile's axes (along from the light towards the tile's first point, the same at every
// level, so that a block's pyramid lies in its parent's): a ball of radius m about q (from the
// light) at depth s = q.along > m has its x = q.u / s between (q.u - m) / (s -+ m) and
// (q.u + m) / (s -+ m), the denominator taken to make each bound the wider. A block with a point
// at or behind the light's depth, or farther than 1e3 times the light's largest coordinate, or one
// seen at more than 10 (84 degrees) off the axis, gets no list (its rays walk the BVH): blob_beam's
// slack covers the rounding of nearer points and narrower pyramids only. The tile's level takes
// the axes and every point's slopes once (Lists::slopes: each point was taken again by its quarter
// and its block, with four divisions, 15.6 M of pov:blob1a's 380 M instructions); a quarter and a
// block take the bounds of their points' slopes, the same numbers.
void ShadowBeams::build_pyramid(int level, const Axes& light, size_t k, const Point* points,
                                int begin, int end, Lists& lists) const {
  std::vector<BlobBeam>& out = lists.level[level];
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const int o : blob_objects_)
    out[k * objects_ + o].valid = out[k * objects_ + o].clear = out[k * objects_ + o].shut = false;
  Slopes* slopes = lists.slopes.data() + k * size_t(lists.points);
  if (level == 0) {
    Axes& a = lists.pyramids[k];
    a.point = false;  // no pyramid (below) until the axes are known
    if (end == begin) return;
    const Vec3 to_tile = lists.origin - light.position;
    const double reach = length(to_tile);
    if (!(reach > 0)) return;
    a = axes(to_tile / reach, true, light.position);
    const double apex = max_abs(a.position);
    for (int i = begin; i < end; ++i) {
      const Vec3 q = points[i].p - a.position;
      const double m = points[i].margin * (1 + 1e-9);
      const double s = dot(q, a.along), x = dot(q, a.u), y = dot(q, a.v);
      Slopes& b = slopes[i];
      b.held = s > 2 * m && max_abs(points[i].p) + m <= 1e3 * apex;
      if (!b.held) continue;
      const auto low = [&](double c) { return (c - m) / (c - m >= 0 ? s + m : s - m); };
      const auto high = [&](double c) { return (c + m) / (c + m >= 0 ? s - m : s + m); };
      b.x0 = low(x), b.x1 = high(x), b.y0 = low(y), b.y1 = high(y);
    }
  }
  if (end == begin) return;
  const Axes& a = lists.pyramids[k];
  if (!a.point) return;
  double x0 = kInf, x1 = -kInf, y0 = kInf, y1 = -kInf;
  for (int i = begin; i < end; ++i) {
    const Slopes& b = slopes[i];
    if (!b.held) return;
    x0 = std::min(x0, b.x0), x1 = std::max(x1, b.x1);
    y0 = std::min(y0, b.y0), y1 = std::max(y1, b.y1);
  }
  if (!(std::max(std::max(-x0, x1), std::max(-y0, y1)) <= 10)) return;
  Frustum f;
  f.eye = a.position;
  f.forward = a.along;
  f.corner[0] = a.along + a.u * x0 + a.v * y0;
  f.corner[1] = a.along + a.u * x1 + a.v * y0;
  f.corner[2] = a.along + a.u * x0 + a.v * y1;
  f.corner[3] = a.along + a.u * x1 + a.v * y1;
  const ShadowPrism pyramid{a.position, a.along, a.u, a.v, x0, x1, y0, y1, 0};
  for (const int o : blob_objects_) {
    BlobBeam& list = out[k * objects_ + o];
    // The parent's pyramid holds this one (the same axes, a subset of its points).
    const BlobBeam* parent = level > 0 ? &lists.level[level - 1][k * objects_ + o] : nullptr;
    tracers_[o].toward_beam(f, pyramid, parent, &list);
    if (level == kLevels - 1) tracers_[o].shadow_blockers(&list);
  }
}

void ShadowListsOnDemand::build() {
  static_assert(ShadowBeams::kLevels == 3);
  const int b = wanted_, q = b / 4;
  if (!tile_) beams_.build(0, points_, starts_[0], starts_[16], lists_), tile_ = true;
  if (quarter_ != q)
    beams_.build(1, points_, starts_[q * 4], starts_[q * 4 + 4], lists_), quarter_ = q;
  beams_.build(2, points_, starts_[b], starts_[b + 1], lists_), block_ = b;
  view_.lists = lists_.level[ShadowBeams::kLevels - 1].data();
}

}  // namespace softtrace

// The shadow rays of a block of pixels towards a directional light share their approach to a sum
// of polynomial blobs, as the block's camera rays share theirs: once a tile's camera rays are
// traced, their lit points are known, and the blobs their shadow rays may meet are listed once for
// the tile (ObjectTracer::shadow_beam), then narrowed for its quarters and their quarters. Each
// shadow ray of a block takes its stretches' blobs from the block's list instead of walking the
// sum's BVH; a ray the list does not hold (BlobBeam::holds) walks as before, so the answers are
// the walk's to the bit. A block's list of positive blobs also names up to two balls that may
// block its rays alone (ObjectTracer::shadow_blockers), which each ray asks first; a tile's or a
// quarter's list that one such ball shuts is its blocks' list, and they build none. A block whose
// prism misses the sum's box or whose list holds no blob (or whose parent's does either) is clear
// (BlobBeam::clear): its rays are answered with no trace and no check of their own, which holds
// because shade() lifts them from the very points given here (ShadowLists::p, offset). Most of a
// floor's blocks beside a cloud are.
// The shadow rays of a block towards a point or spot light converge on its position: their list
// is the camera's (ObjectTracer::blob_beam) for the pyramid from the light through the block's
// lit points, each ray finding its stretches' blobs by their distance from the light
// (BlobBeam::toward); its blocks pick blockers as well.
#pragma once

#include <vector>

#include "render/lights.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace softtrace {

class ShadowBeams {
 public:
  // A shadow ray's origin: within `margin` of `p` (the lifted point of shade()).
  struct Point {
    Vec3 p;
    double margin;
  };
  static constexpr int kLevels = 3;  // a tile, its quarters and theirs, as the camera's beams
  // A sum of at most this many blobs takes no lists: a shadow ray's walk then takes every blob's
  // term over its whole way at once (BlobSum::kListed), and a list would spare it a few of those
  // terms, for less than the list's build (a tile's pyramid and its quarters' and blocks') and
  // each ray's check that it holds it cost. Callgrind, whole process, 1 thread, 320x240, lists
  // against none: pov:blob (3 blobs) +10.7 %, molecule (3) +8.2 %, old_syntax (4) +6.8 %, blob1a
  // (3) +2.6 %, blob1c (4) +2.9 %, sheared (5) +1.8 %, candle (7) +0.5 %; but blob1b (11) -10.9 %.
  static constexpr int kFewBlobs = 8;
  // A rectangle on a directional light's axes (u, v) and a depth along it: a point's ball's
  // (x -+ m, y -+ m, z - m) or an object's box's (z: the farthest corner's).
  struct Extent {
    double x0, x1, y0, y1, z;
  };
  // Where a point's ball is seen from a point light, on the tile's pyramid's axes: its x between
  // x0 and x1 times the depth, its y between y0 and y1; `held` false where the point gets no list
  // (build_pyramid).
  struct Slopes {
    double x0, x1, y0, y1;
    bool held;
  };
  struct Axes {
    Vec3 along, u, v;  // along: towards the light, to the bit as light_arrival's
    bool point;        // a point or spot light at `position`: along, u and v are the tile's
    Vec3 position;
  };
  // One thread's lists: per level, per light with lists, one per object.
  struct Lists {
    Vec3 origin;  // the tile's: the prisms' coordinates are taken from it
    std::vector<BlobBeam> level[kLevels];
    // The tile's, on its origin and the axes of each directional light (k): its points' balls
    // ([k * points + i]) and the objects' boxes ([k * objects + o]). A quarter's or a block's
    // prism is the bounds of its points' (the same numbers, computed once a tile), and meets an
    // object's box as the tile's box says.
    std::vector<Extent> balls, boxes;
    // And for each point or spot light (k): the tile's pyramid's axes (pyramids[k]; held false
    // where it has none) and its points' slopes on them ([k * points + i]), computed once a tile:
    // a quarter's or a block's pyramid is their bounds over its points.
    std::vector<Axes> pyramids;
    std::vector<Slopes> slopes;
    int points = 0;
    // Per directional light and object ([k * objects + o]): which shut list of the tile or of the
    // current quarter its blocks take (Lent, build_prism).
    std::vector<char> lent;
  };

  ShadowBeams(const Scene& scene, const SceneTracers& tracers);
  // Whether any light and object takes lists: a directional, point or spot light with shadows
  // (and no area) and a sum of more than kFewBlobs polynomial blobs (shadow_beams.cpp).
  bool active() const { return !lights_.empty() && !blob_objects_.empty(); }
  // The lists of `level` for the block whose shadow rays start near points[begin, end), from those
  // of the block above it (level - 1), or for level 0 (a tile, whose origin is points[0]; begin is
  // 0) from the sums' BVHs. `points` are the tile's at every level: a quarter's and a block's are
  // ranges of them. A block with no points gets no lists.
  void build(int level, const Point* points, int begin, int end, Lists& lists) const;
  // The lists of `level` seen as a block's (ShadowListsOnDemand's for shade()); the caller sets
  // the shaded point (one of the block's, as given to build()) in ShadowLists::p and offset.
  ShadowLists view(int level, const Lists& lists) const {
    return {slot_.data(), lists.level[level].data(), objects_, {0, 0, 0}, 0};
  }

 private:
  // Whose list a directional light's block takes for an object: its own, or the tile's or its
  // quarter's, where one blocker shuts that (shut_and_lend), which then lies in the blocks' level.
  enum Lent : char { kOwn, kTile, kQuarter };
  // The axes about `along` (u across the coordinate axis least aligned with it).
  static Axes axes(const Vec3& along, bool point, const Vec3& position);
  void build_prism(int level, const Axes& a, size_t k, const Point* points, int begin, int end,
                   Lists& lists) const;
  // Whether the tile's points' prism certainly misses every object's box (build_prism's test).
  bool misses_boxes(const Axes& a, const Point* points, int begin, int end, const Vec3& origin,
                    const Extent* boxes) const;
  // Whether one blocker shuts `list` (of light k and object o, the tile's or a quarter's, whose
  // points' balls' tops reach z1); if so, it moves to the blocks' level (Lists::lent).
  void shut_and_lend(int level, size_t k, int o, double z1, Lists& lists) const;
  void build_pyramid(int level, const Axes& a, size_t k, const Point* points, int begin, int end,
                     Lists& lists) const;
  const SceneTracers& tracers_;
  int objects_;
  std::vector<int> slot_;          // per scene light: its index in lights_, or -1
  std::vector<Axes> lights_;       // the lights with lists
  std::vector<int> blob_objects_;  // the objects that are sums of polynomial blobs
};

// A tile's lists as shade() takes them, block by block, each built when its shadow rays first ask
// for them (of()): a block's, and its quarter's and the tile's above it, when one of the block's
// points casts a shadow ray, instead of every level of every block with points before its pixels
// are shaded. A block whose points all face away from the lights casts none (a cloud's dark side:
// meets10 at 640x480 has 91,001 hits and 52,466 shadow rays), and needs no list. The lists built
// are the ones the frame's order would build, from the same points in the same order (a tile's
// first, then a quarter's, then its blocks'), so each ray gets the same list; a level skipped
// leaves nothing a later one reads (a quarter's list is rebuilt for each quarter, a block's for
// each block).
class ShadowListsOnDemand {
 public:
  // The tile's points (block b's are points[starts[b], starts[b + 1])), whose lists go in `lists`.
  ShadowListsOnDemand(const ShadowBeams& beams, const ShadowBeams::Point* points, const int* starts,
                      ShadowBeams::Lists& lists)
      : beams_(beams),
        points_(points),
        starts_(starts),
        lists_(lists),
        view_(beams.view(ShadowBeams::kLevels - 1, lists)) {}
  // Block b's points are shaded next (of the tile's 16, a quarter's four after one another): before
  // the first of().
  void block(int b) { wanted_ = b; }
  // The point shaded next, one of the block's as given to ShadowBeams (ShadowLists::p, offset).
  void at(const ShadowBeams::Point& point) {
    view_.p = point.p;
    view_.offset = point.margin;
  }
  const Vec3& p() const { return view_.p; }
  double offset() const { return view_.offset; }
  // The block's lists of scene light `light`, one per object (ShadowLists::of), built first where
  // this is the block's first shadow ray towards a light with lists.
  const BlobBeam* of(int light) {
    if (view_.slot[light] < 0) return nullptr;
    if (block_ != wanted_) build();
    return view_.of(light);
  }

 private:
  // Builds what block wanted_'s lists need, and points the view at the blocks' level.
  void build();

  const ShadowBeams& beams_;
  const ShadowBeams::Point* points_;
  const int* starts_;
  ShadowBeams::Lists& lists_;
  ShadowLists view_;
  bool tile_ = false;
  int quarter_ = -1, block_ = -1, wanted_ = -1;
};

}  // namespace softtrace

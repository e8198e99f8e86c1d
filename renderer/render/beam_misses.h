// Background beams: a block of camera rays from one eye (a beam, Frustum) that certainly meets no
// object's box, so that its pixels are written as misses without a ray each (frame.cpp). Most of
// a sparse frame is background (meets1 at 640x480: 94 % of its pixels), and each such pixel's
// ray cost a camera ray, the scene's intersect and a box clip to learn that it met nothing.
//
// The certificate must give each ray the answer its trace gives, counters included: no hit and
// no work (TraceCounters all zero: a ray that misses every box is clipped away before any work is
// counted, clip_to_box, CsgTracer::spans, Embree's culls). So every box is missed with a margin no
// rounding can eat: clip_to_box's computed answer is the exact answer for the box moved by a few
// ulps of its coordinates and the eye's, a ray's computed direction lies within a few ulps of
// the corners' convex hull (its image-plane column and row lie between the beam's corners', which
// ViewCamera computes by the same monotone steps), a primitive's analytic test and Embree's float
// triangles are off by far less than 1e-5 of the coordinates. Unbounded objects (a plane) are
// never certified missed.
#pragma once

#include <vector>

#include "math/box.h"
#include "render/camera.h"
#include "trace/tracer.h"

namespace softtrace {

class BeamMisses {
 public:
  // The scene's objects' boxes: for each object its box (Embree's and a CSG's) and its field's
  // (where its tracer clips rays). `camera`: where the boxes are seen, so that a beam where one
  // may be seen is not tested at all, and the eye every beam's rays leave; a camera without one
  // (orthographic, or with a lens) has no beams, and none is certified.
  BeamMisses(const SceneTracers& tracers, const ViewCamera& camera);

  // Whether no ray of `f` (from its eye at t >= 0, in a direction a convex combination of its
  // corners' up to rounding) enters any object's box: each box lies past one of the beam's four
  // side planes or behind the eye, with the margin above. `f` is the camera's beam through the
  // pixels [x0, x1) x [y0, y1); where those meet a box's outline as the camera sees it (padded
  // by two pixels), the answer is false without the test (which would mostly fail there).
  bool misses(const Frustum& f, int x0, int y0, int x1, int y1) const;
  // Whether misses() may ever say true: false where an object has no finite box or one across
  // the eye's plane (a floor's, whose box holds the eye), or where the camera has no single eye,
  // so that a caller asks nothing of each beam (the call was 0.07 % of the floor frame's
  // process).
  bool ever() const { return !never_; }

  // Whether `f` misses `box` so (exposed for the tests).
  static bool misses_box(const Frustum& f, const Box& box);

  // The planes through an eye outside a box and the box's silhouette edges (the hexagon, or
  // rectangle, it is seen as): a beam all of whose rays leave one of them on the outside, with
  // the margin of beam_misses.h, misses the box. This is the test where the beam meets the box's
  // padded rectangle on screen (`seen_`), whose corners lie outside the hexagon.
  struct Outline {
    struct Side {
      Vec3 n;        // the box on its positive side
      double limit;  // a ray of direction d with n . d < -limit |d| misses the box
    };
    int sides = 0;
    Side side[6];
  };
  static Outline outline_of(const Vec3& eye, const Box& box);
  // Whether every ray of `f` lies past one of its sides so; `f`'s eye must be the one the outline
  // was made for (outline_of's), as every beam of the camera's is (misses()).
  static bool beyond(const Outline& outline, const Frustum& f);

 private:
  // An object without a finite box, or one across the eye's plane: no beam is certified.
  bool never_ = false;
  Box all_;                // every object's box
  std::vector<Box> each_;  // each object's, where the scene has few (misses() tries them too)
  // Pixel rectangles [x0, x1] x [y0, y1] holding the boxes' outlines (each_'s, else all_'s).
  struct Seen {
    double x0, y0, x1, y1;
  };
  std::vector<Seen> seen_;
  Outline outline_;  // all_'s seen from the camera's eye, where each_ is empty
};

}  // namespace softtrace

// The camera rays of one block of a lone blob sum whose list holds no blob (EmbreeScene::unmet),
// or a few balls they may pass (EmbreeScene::passable), answered with what the block's rays share
// taken once: EmbreeScene::unmet_rays. Each such ray's answer is no hit, and its counters are the
// sum's box clip and its counted stretches (ObjectTracer::first_hit_unlisted); through
// intersect_unmet each of meets1's 160,532 such rays at 640x480 took some 180 instructions in
// three calls (a TraceHit cleared, the box's corners taken from the eye, the counters added field
// by field) beside the pixel's own.
//
// answer() is intersect_unmet's (and intersect_passing's) arithmetic in its order, to the bit:
// the same forward cosine and clear depth, the same slabs (each box side less the eye, which a
// ray from the eye subtracts alike), the same stretches. Where intersect_unmet would not answer
// (a ray not forward, not from the eye, or at the ray limit), or where a passable block's ray
// does not certainly pass its balls, answer() is false and the ray is traced as before.
#pragma once

#include <algorithm>
#include <limits>

#include "math/box.h"
#include "math/vec.h"
#include "trace/tracer.h"
#include "trace/unlisted_stretches.h"

namespace softtrace {

struct UnmetRays {
  Vec3 eye;          // the list's, every ray's origin
  Vec3 forward;      // the camera's (BeamClear::forward)
  Box box;           // the sum's (ObjectTracer::box): its clip
  Vec3 lo_from_eye;  // box.lo - eye and box.hi - eye: the clip's differences, taken once
  Vec3 hi_from_eye;  //
  double depth = 0;  // the beam's certified forward depth of the sum (BeamClear::depth)
  double tfar = std::numeric_limits<double>::infinity();  // no primitive's hit bounds the search
  // A passable block's: the sum's tracer and list, whose balls each ray must pass first
  // (ObjectTracer::passes_listed_balls); null for an unmet block's.
  const ObjectTracer* passes = nullptr;
  const BlobBeam* list = nullptr;

  // Whether `ray` is answered so, with no hit; then `work` holds its counters (from zero).
  bool answer(const Ray& ray, TraceCounters& work) const {
    if (ray.o.x != eye.x || ray.o.y != eye.y || ray.o.z != eye.z) return false;
    return answer_from_eye(ray, work);
  }

  // answer() for a ray whose origin is `eye`: a caller whose rays all leave the eye (a pinhole
  // camera's, whose eye the block's list was made for) skips its three tests a ray.
  bool answer_from_eye(const Ray& ray, TraceCounters& work) const {
    const Vec3& d = ray.d;
    const double cos_forward = dot(d, forward);
    if (!(cos_forward > 0)) return false;
    if (passes && !passes->passes_listed_balls(ray, *list)) return false;
    work = TraceCounters{};
    // clip_to_box from 0 to tfar.
    double t0 = 0, t1 = tfar;
    for (int i = 0; i < 3; ++i) {
      if (d[i] == 0) {
        if (eye[i] < box.lo[i] || eye[i] > box.hi[i]) return true;
        continue;
      }
      const double inv = 1 / d[i];
      double a = lo_from_eye[i] * inv, b = hi_from_eye[i] * inv;
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    if (!(t0 <= t1)) return true;
    work.entered_box = true;
    // A depth of 0 (a blob sum's beams certify none) leaves t0, which is never below +0, as it
    // is: its division is not made.
    if (depth != 0) t0 = std::max(t0, depth / cos_forward);
    if (t0 > t1) return true;
    // ObjectTracer::unlisted_stretches' count, from work's zero evaluations; at the ray limit
    // intersect() answers the ray (its give-up).
    return count_unlisted_stretches(t0, t1, work);
  }
};

}  // namespace softtrace

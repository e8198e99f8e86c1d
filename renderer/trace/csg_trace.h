// Tracing a CSG object (scene/trace_target.h TracedObject, loaded as scene.h Csg): along a ray, the
// spans where it is inside each operand (a shape's analytically, a closed mesh's from all its
// triangles' crossings (trace/mesh_crossings.h), a field's from its certified crossings, entry,
// exit, entry...), combined by the operation down the tree; the first end of a
// combined span inside the ray's range is the hit, on the surface of the operand that bounds the
// result there.
//
// A field's crossings are each the certified first crossing of ObjectTracer::first_hit: its entry
// the first point inside its solid (f on the inside side of iso, within its `bounds`), its exit
// the first point past that inside the complement (a second tracer of the same field with the
// inside sign turned), each search restarting just past (1/1000 of the footprint) the crossing
// before it, so no stretch of the ray is skipped and no crossing is found twice. A field clipped
// by its bounds enters or leaves through the box's face.
#pragma once

#include <memory>
#include <vector>

#include "trace/tracer.h"

namespace softtrace {

struct CsgHit {
  bool hit = false;
  double t = 0;
  Vec3 normal;  // outward from the result's solid, unit (a subtracted operand's, turned)
  // The face (TracedObject::face) of the operand, a field, a shape or a mesh, whose surface it is:
  // the face takes its material.
  int face = -1;
  // The point in the face's own frame (the world's but inside a placed CSG): where its
  // component materials are weighed.
  Vec3 face_point;
};

struct CsgNode;

// Where the ray is inside a solid: t in [t0, t1], each end on the surface of `leaf` (an operand
// that is a field, a shape or a mesh), or on no surface where the span runs past the range
// searched.
struct CsgEnd {
  const CsgNode* leaf = nullptr;  // the node of that operand; null: no surface
  bool on_box = false;            // a field's end on its bounds' face
  bool flip = false;              // the surface of a subtracted operand: its normal turns
  Vec3 normal;                    // a shape's or a mesh's normal there (outward from it)
};
struct CsgSpan {
  double t0, t1;
  CsgEnd e0, e1;
};

class CsgTracer {
 public:
  // `object` is a CSG (TracedObject::csg()); the tracer keeps what it needs of it.
  CsgTracer(const TracedObject& object, LipschitzMode mode);
  ~CsgTracer();
  CsgTracer(const CsgTracer&) = delete;
  CsgTracer& operator=(const CsgTracer&) = delete;

  // The first surface point of the result in [tnear, tfar] (a ray that starts inside it finds
  // the exit). Shadow rays ask the same. The work is added to `work`.
  CsgHit first_hit(const Ray& ray, double tnear, double tfar, TraceCounters& work) const;
  // The result's spans within [tnear, tfar], in order (for tests).
  std::vector<CsgSpan> spans(const Ray& ray, double tnear, double tfar, TraceCounters& work) const;

 private:
  Box bounds_;
  std::unique_ptr<CsgNode> root_;
};

}  // namespace softtrace

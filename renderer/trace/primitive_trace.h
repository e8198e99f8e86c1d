// Exact ray intersection with the plain primitives (scene/primitive.h): the span of a ray inside
// a primitive's solid, from which the first surface point follows. Analytic: the ray is taken to
// the shape's own space (t is unchanged by an affine map), where each shape is a quadric or
// slabs.
#pragma once

#include "scene/primitive.h"
#include "trace/tracer.h"

namespace softtrace {

// Where a ray is inside a solid: t in [t0, t1] (either may be infinite; t0 > t1: nowhere), with
// the outward unit normals (world space) of the surface at each end. A disc, which has no inside,
// gives its one crossing as t0 = t1.
struct SolidSpan {
  double t0 = 1, t1 = 0;
  Vec3 n0, n1;
  bool empty() const { return !(t0 <= t1); }
};
SolidSpan solid_span(const Primitive& shape, const Ray& ray);

struct PrimitiveHit {
  bool hit = false;
  double t = 0;
  Vec3 normal;  // outward, unit, world space
};
// The nearest surface point in [tnear, tfar], within kMaxPosition of the origin (an infinite
// plane is drawn to there: scene/primitive.h).
PrimitiveHit first_hit(const Primitive& shape, const Ray& ray, double tnear, double tfar);
// Whether first_hit finds a surface point: a shadow ray's question, answered without turning a
// normal to the world (a square root and a division for each end of the span).
bool occludes(const Primitive& shape, const Ray& ray, double tnear, double tfar);

}  // namespace softtrace

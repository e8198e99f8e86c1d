// Exact ray intersection with the plain primitives (scene/primitive.h): the span of a ray inside
// a primitive's solid, from which the first surface point follows. Analytic: the ray is taken to
// the shape's own space (t is unchanged by an affine map), where each shape is a quadric or
// slabs.
#pragma once

#include <cmath>
#include <limits>

#include "scene/primitive.h"
#include "scene/ranges.h"
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

// Whether the point at t is a surface point first_hit may report: in [tnear, tfar], within
// kMaxPosition of the origin.
inline bool reachable(const Ray& ray, double t, double tnear, double tfar) {
  return t >= tnear && t <= tfar && std::isfinite(t) && max_abs(ray.o + ray.d * t) <= kMaxPosition;
}

// An unplaced plane (a floor; every camera and shadow ray tests it) without the general span:
// the solid's span on a ray has one finite end, where the ray crosses the plane, whichever way it
// goes, and that end's normal is the plane's. Its t if reachable, else NaN. Inline, as are
// first_hit and occludes for it below: a floor's test on each of a frame's 560,000 camera and
// shadow rays was mostly the calls' own work.
// `nd`: dot(s.normal, ray.d), which a caller whose rays share a direction takes once.
// unplaced_plane_gap(s, o): the division's numerator, distance - dot(n, o), the same for every
// ray from o (a camera's eye: BeamClear::floor_gap).
inline double unplaced_plane_gap(const Primitive& s, const Vec3& o) {
  return s.distance - dot(s.normal, o);
}
inline double unplaced_plane_end(const Primitive& s, const Ray& ray, double nd, double tnear,
                                 double tfar) {
  if (nd == 0) return std::numeric_limits<double>::quiet_NaN();  // all inside or all outside
  const double t = unplaced_plane_gap(s, ray.o) / nd;
  return reachable(ray, t, tnear, tfar) ? t : std::numeric_limits<double>::quiet_NaN();
}
inline double unplaced_plane_end(const Primitive& s, const Ray& ray, double tnear, double tfar) {
  return unplaced_plane_end(s, ray, dot(s.normal, ray.d), tnear, tfar);
}
// unplaced_plane_end for a ray whose points at |t| <= reach are known to lie within
// kMaxPosition (a camera beam's rays, BeamClear::reach): reachable's answer without the point's
// max_abs there. A function of its own: the reach's test in the others' inlined copies cost the
// cloud frame's shading registers.
// `gap`: unplaced_plane_gap(s, ray.o), which a caller whose rays share their origin takes once,
// or NaN (taken here).
inline double unplaced_plane_end_within(const Primitive& s, const Ray& ray, double tnear,
                                        double tfar, double reach, double gap) {
  const double nd = dot(s.normal, ray.d);
  if (nd == 0) return std::numeric_limits<double>::quiet_NaN();
  const double t = (std::isnan(gap) ? unplaced_plane_gap(s, ray.o) : gap) / nd;
  if (t >= tnear && t <= tfar && std::abs(t) <= reach) return t;
  return reachable(ray, t, tnear, tfar) ? t : std::numeric_limits<double>::quiet_NaN();
}
inline bool unplaced_plane(const Primitive& s) {
  return s.unplaced && s.shape == Primitive::Shape::Plane;
}

// first_hit and occludes of any other primitive: from its span in its own space.
PrimitiveHit spanned_first_hit(const Primitive& shape, const Ray& ray, double tnear, double tfar);
bool spanned_occludes(const Primitive& shape, const Ray& ray, double tnear, double tfar);

// The nearest surface point in [tnear, tfar], within kMaxPosition of the origin (an infinite
// plane is drawn to there: scene/primitive.h).
inline PrimitiveHit first_hit(const Primitive& shape, const Ray& ray, double tnear, double tfar) {
  if (!unplaced_plane(shape)) return spanned_first_hit(shape, ray, tnear, tfar);
  const double t = unplaced_plane_end(shape, ray, tnear, tfar);
  if (std::isnan(t)) return {};
  return {true, t, shape.world_normal};  // world_normal(shape, shape.normal), computed once
}
// Whether first_hit finds a surface point: a shadow ray's question, answered without turning a
// normal to the world (a square root and a division for each end of the span).
inline bool occludes(const Primitive& shape, const Ray& ray, double tnear, double tfar) {
  if (!unplaced_plane(shape)) return spanned_occludes(shape, ray, tnear, tfar);
  return !std::isnan(unplaced_plane_end(shape, ray, tnear, tfar));
}

}  // namespace softtrace

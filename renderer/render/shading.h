// Shading a hit with its object's material (POV-Ray 3.7's finish, docs/math.md "Finishes"):
// ambient, diffuse with brilliance, phong and specular highlights from each light past the
// shadows, and mirror reflection traced up to the scene's max_trace_level.
#pragma once

#include <algorithm>
#include <atomic>

#include "render/cancel.h"
#include "render/finish.h"
#include "render/lights.h"
#include "render/shadow_beams.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"
#include "trace/tracer.h"

namespace softtrace {

struct Shaded {
  Vec3 color;
  Vec3 normal;  // unit, facing the viewer
  Vec3 albedo;  // the material's colour
};

// The normal comes from the hit object's tracer; shadow and reflected rays go through `rt`, each
// one's work added to `secondary`. Once `cancel` (render/cancel.h) is set no more rays are cast
// and the colour is moot. `level` is POV-Ray's trace level: 1 for a camera ray. `weight` is
// POV-Ray's ray weight, the most this ray's colour can count in the pixel (1 for a camera ray):
// a mirror or transmitted ray whose weight would fall below adc_bailout is not traced.
// `interiors`: the ray's interior list (trace/interiors.h; none for a camera ray), which its
// shadow, mirror and transmitted rays take on. `shadow`: the shadow lists of the camera ray's
// block of pixels (shadow_beams.h), or none; with them, the hit's point and its rays' offset are
// taken from `shadow` (the frame computed them for the lists, by the same arithmetic).
Shaded shade(const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
             const TraceHit& hit, RayWork& secondary, const std::atomic<bool>* cancel = nullptr,
             int level = 1, double weight = 1, const Interiors* interiors = nullptr,
             ShadowListsOnDemand* shadow = nullptr);

// The least offset of a hit's rays on `obj` where it is the object's alone: 1e-4 of a field's or
// a mesh's box diagonal; -1 for a primitive, whose offset depends on the point (ray_offset). The
// frame takes it once per object.
inline double own_lift(const SceneObject& obj) {
  return obj.field || obj.mesh ? 1e-4 * obj.bounds.diagonal() : -1.0;
}

// ray_offset's first term below for an object whose own_lift is < 0 (no field nor mesh: a
// primitive), by p's size alone; also for a caller that kept own_lift and knows it.
inline double unowned_lift(const Vec3& p) {
  return 1e-9 * std::max(1.0, max_abs(p));
}

// How far from a hit at p on `obj` (the face's object for a CSG) its shadow and mirror rays start
// along the normal (shade()), the camera ray's footprint there being cone0.
// Inline: it runs twice for every shaded point (the frame's shadow lists ask it too).
inline double ray_offset(const SceneObject& obj, const Vec3& p, double cone0) {
  const double own = own_lift(obj);
  return std::max(!(own < 0) ? own : unowned_lift(p), cone0);
}

// The short way, inline so that the frame's loop over its camera hits (frame.cpp, samples) takes
// it without shade()'s call, look-ups and tests: the same operations in the same order, so the
// same bits as shade().

// Whether every point of `obj` (an object, or a CSG's face's object) is shaded the short way: an
// opaque matte-or-highlighted material of its own (no components, no mirror, nothing
// transmitted), no ambient occlusion, no transparency in the scene. Most of a frame's points are
// such (the 1000-blob frame and its floor: all of them). Constant over a frame.
inline bool shades_plain(const Scene& scene, const SceneObject& obj) {
  const Material& m = obj.material;
  return !scene.transparent && !obj.components && scene.image.occlusion.samples <= 0 &&
         !transparent(m) && !m.fresnel && !reflects(m.reflection);
}

// The normal shade() shades with at p: the hit object's (a primitive's or a CSG's came with its
// hit; a field's gradient walk also gives its components' values in `terms`, where asked),
// facing the viewer.
[[gnu::always_inline]] inline Vec3 facing_normal(const ObjectTracer* tracer, const Ray& ray,
                                                 const TraceHit& hit, const Vec3& p,
                                                 double* terms) {
  Vec3 n = !tracer           ? hit.normal
           : hit.on_box_face ? tracer->box_face_normal(p)
                             : tracer->normal(p, terms, hit.blobs);
  if (dot(n, n) == 0) n = -ray.d;  // a flat spot of the field (length 0): face the viewer
  // Seen from inside (clipped solids, transparent ones): shade the side we see.
  if (dot(n, ray.d) > 0) n = -n;
  return n;
}

// Shadow rays keep the camera ray's footprint: they decide what this pixel shows. They leave the
// surface by that footprint's radius (at least 1e-4 of the object's box), far more than the hit's
// error (1e-3 of it): nearer, the tracer would have to resolve the very surface it leaves.
inline double footprint_at(const Ray& ray, const TraceHit& hit) {
  return ray.cone_at(hit.t);
}

// A point, spot or area light l's diffuse term (into `light`) and highlight (into `shine`) at a
// shades_plain() point p, normal n facing the viewer along d, its shadow rays leaving from `lifted`
// with the block's lists of light `li` in `shadow` (or none): shade_plain's and PlainFloor's
// (plain_floor.h) light.
[[gnu::always_inline]] inline void add_positional_light(
    const Light& l, const Material& m, const Vec3& d, const Vec3& p, const Vec3& n,
    const Vec3& lifted, double cone0, double cone, const EmbreeScene& rt, RayWork& secondary,
    const std::atomic<bool>* cancel, ShadowListsOnDemand* shadow, int li, Vec3& light,
    Vec3& shine) {
  LightArrival at;
  if (!light_arrival(l, p, lifted, at)) return;
  const double cosine = dot(n, at.to_light);
  if (cosine <= 0) return;
  Vec3 arrived = at.light;
  const double seen = light_visibility(l, at, lifted, cone0, cone, rt, secondary, cancel,
                                       shadow ? shadow->of(li) : nullptr);
  if (seen == 0) return;
  if (seen != 1) arrived = at.light * seen;
  light += diffuse_light(m, cosine, arrived);
  // A matte finish's highlights are zero (highlights()), and `shine` is added only where the
  // finish has some: not summed.
  if (l.shadows && (m.phong > 0 || m.specular > 0))
    shine += phong_and_specular(m, n, d, at.to_light, arrived);
}

// shade()'s light loop and colour for a shades_plain() point at p, normal n facing the viewer
// along d, its shadow rays leaving from `lifted`: without the blends', the transmitted and the
// mirror rays' state (130 instructions a point less).
[[gnu::always_inline]] inline Shaded shade_plain(const Scene& scene, const EmbreeScene& rt,
                                                 const Vec3& d, const Vec3& p, const Vec3& n,
                                                 const Vec3& lifted, double cone0, double cone,
                                                 const Material& m, RayWork& secondary,
                                                 const std::atomic<bool>* cancel,
                                                 ShadowListsOnDemand* shadow) {
  Vec3 light{0, 0, 0}, shine{0, 0, 0};
  // The lights' array and count read once: the shadow ray's call between two lights would have
  // the loop read the vector again (10 instructions a point of the floor's frame).
  const Light* const lights = scene.lights.data();
  const size_t count = scene.lights.size();
  for (size_t li = 0; li < count; ++li) {
    const Light& l = lights[li];
    if (cancel_requested(cancel)) break;
    if (l.type == Light::Type::Ambient) {
      light += mul(m.ambient, l.color * l.intensity);
      continue;
    }
    add_positional_light(l, m, d, p, n, lifted, cone0, cone, rt, secondary, cancel, shadow, int(li),
                         light, shine);
  }
  Vec3 color = mul(m.color, light);
  // A matte finish's shine is zero (highlights()): no three comparisons to find that out.
  if ((m.phong > 0 || m.specular > 0) && (shine.x != 0 || shine.y != 0 || shine.z != 0))
    color += shine;
  return {color, n, m.color};
}

// shade() for a camera ray's hit on a shades_plain object (no CSG face), given the hit's point
// `p` (ray.o + ray.d * hit.t) and its rays' `offset` (ray_offset(obj, p, cone0)) as shade()
// takes them (the frame's ShadowBeams::Point: the same arithmetic), with the block's shadow
// lists, or none (a frame without ShadowBeams: each shadow ray alone, as shade() traces it).
[[gnu::always_inline]] inline Shaded shade_plain_at(
    const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
    const TraceHit& hit, const Material& m, const Vec3& p, double offset, RayWork& secondary,
    const std::atomic<bool>* cancel, ShadowListsOnDemand* shadow) {
  const Vec3 n = facing_normal(tracers.tracer(hit.object), ray, hit, p, nullptr);
  const double cone0 = footprint_at(ray, hit);
  const Vec3 lifted = p + n * offset;
  return shade_plain(scene, rt, ray.d, p, n, lifted, cone0, ray.cone, m, secondary, cancel, shadow);
}

// shade() for a camera ray's hit on `obj` (its object, no CSG face), shades_plain, with its
// block's shadow lists (their point and offset): shade(scene, tracers, rt, ray, hit, secondary,
// cancel, 1, 1, nullptr, &shadow) to the bit. The frame's loop asks shades_plain once per object
// for the frame, not once per point (shade()'s look-ups, test and call were a tenth of a floor
// point's shading).
[[gnu::always_inline]] inline Shaded shade_plain_hit(
    const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
    const TraceHit& hit, const Material& m, RayWork& secondary, const std::atomic<bool>* cancel,
    ShadowListsOnDemand& shadow) {
  return shade_plain_at(scene, tracers, rt, ray, hit, m, shadow.p(), shadow.offset(), secondary,
                        cancel, &shadow);
}

}  // namespace softtrace

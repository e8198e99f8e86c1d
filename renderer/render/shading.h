// Shading a hit with its object's material (POV-Ray 3.7's finish, docs/math.md "Finishes"):
// ambient, diffuse with brilliance, phong and specular highlights from each light past the
// shadows, and mirror reflection traced up to the scene's max_trace_level.
#pragma once

#include <algorithm>
#include <atomic>

#include "render/lights.h"
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
// block of pixels (lights.h), or none; with them, the hit's point and its rays' offset are taken
// from `shadow` (the frame computed them for the lists, by the same arithmetic).
Shaded shade(const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
             const TraceHit& hit, RayWork& secondary, const std::atomic<bool>* cancel = nullptr,
             int level = 1, double weight = 1, const Interiors* interiors = nullptr,
             const ShadowLists* shadow = nullptr);

// How far from a hit at p on `obj` (the face's object for a CSG) its shadow and mirror rays start
// along the normal (shade()), the camera ray's footprint there being cone0.
// Inline: it runs twice for every shaded point (the frame's shadow lists ask it too).
inline double ray_offset(const SceneObject& obj, const Vec3& p, double cone0) {
  return std::max(
      obj.field || obj.mesh ? 1e-4 * obj.bounds.diagonal() : 1e-9 * std::max(1.0, max_abs(p)),
      cone0);
}

}  // namespace softtrace

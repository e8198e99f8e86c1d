// Transparent materials, POV-Ray 3.7's way (docs/math.md §12.6): the light behind a
// surface passes tinted by its filter and untinted by its transmit (POV's rgbft); a transmitted
// ray bends by Snell's law where the interior's ior differs from the air's, or reflects whole
// (total internal reflection); Fresnel's reflectance can weigh the mirror reflection; shadow rays
// pass through transparent surfaces, tinted by each, without bending (no caustics).
#pragma once

#include <atomic>

#include "render/lights.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"

namespace softtrace {

// POV-Ray's default adc_bailout: a transmitted ray whose light would be less than this (in grey)
// is not traced, nor a mirror or transmitted ray whose weight (shade()) falls below it.
constexpr double kAdcBailout = 1.0 / 255;

// What of the light behind a surface of material `m` passes it, per channel: POV's
// filter * colour + transmit.
inline Vec3 transmitted_color(const Material& m) {
  return m.color * m.filter + Vec3{1, 1, 1} * m.transmit;
}

// POV-Ray 3.7's opacity, 1 - filter - transmit: the share of its ambient and diffuse light a
// surface shows (its highlights and reflection show whole).
inline double opacity(const Material& m) {
  return 1 - (m.filter + m.transmit);
}

// POV-Ray's grey of a colour (0.297 r + 0.589 g + 0.114 b), by which it decides whether a
// transmitted ray is worth tracing.
inline double grey(const Vec3& c) {
  return 0.297 * c.x + 0.589 * c.y + 0.114 * c.z;
}

// The Fresnel reflectance of unpolarised light arriving at the cosine `cos_i` (> 0) on a surface
// whose far side's index of refraction is `ratio` times the near side's; 1 past the critical
// angle.
double fresnel_reflectance(double cos_i, double ratio);

// The direction of unit `d` refracted through a surface of unit normal `n` (facing the ray:
// dot(d, n) < 0) where eta = n_incident / n_transmitted (Heckbert's form of Snell's law). False
// for total internal reflection (`out` is then unchanged).
bool refract(const Vec3& d, const Vec3& n, double eta, Vec3& out);

// How far a secondary ray starts off the surface of `obj` at `p`, for a ray footprint of radius
// `cone0` there: shade()'s rule (1e-4 of a field's or a mesh's box, rounding for a primitive).
double leave_distance(const SceneObject& obj, const Vec3& p, double cone0);

// transmitted_color of the surface `hit` along `ray` (a blend's components' mixed by their
// weights there).
Vec3 surface_transmission(const Scene& scene, const Ray& ray, const TraceHit& hit);

// The colour of the light that travels from `tnear` to `distance` along `ray` (unit direction):
// 1 where nothing is in the way, 0 past an opaque surface, else the product of the transmitted
// colours of the transparent surfaces it crosses. `inside`: the interiors the ray starts in (the
// shaded ray's, interiors.h), entered or left at each surface as POV-Ray's shadow rays do. The
// ray's work is added to `shadow` as one ray. Nested and overlapping transparent solids are
// crossed surface by surface (past 64 surfaces, or Interiors::kMax deep, the light counts as
// blocked).
Vec3 shadow_filter(const Scene& scene, const EmbreeScene& rt, const Ray& ray, double tnear,
                   double distance, const Interiors& inside, RayWork& shadow);

// Where a transmitted ray goes at a surface of `object` (its interior's index of refraction
// `ior`) that a ray travelling in `in` crosses, by POV-Ray 3.7's interior list
// (Trace::ComputeRefraction): from the air into it; out of the innermost interior into the next
// one out (or the air); out of an interior that is not the innermost (overlapping objects: the
// overlap counts as the one entered last, so the ray stays in its medium, ratio 1); or into it
// from the innermost. `eta`: n_incident / n_transmitted. False where `in` is Interiors::kMax
// deep and the object is not in it (no ray is traced).
struct Crossing {
  Interiors next;  // the transmitted ray's list
  double eta;
};
bool cross(const Interiors& in, int object, double ior, Crossing& out);

// The index of refraction of the far side over the near one's that Fresnel's reflectance takes at
// a surface of `object` (ior `ior`) that a ray travelling in `in` meets: POV-Ray 3.7's
// Trace::ComputeRelativeIOR, to the letter (leaving an inner object for an outer one it takes the
// innermost interior's ior over the object's, which is 1 where the object is the innermost).
double fresnel_ratio(const Interiors& in, int object, double ior);

// light_visibility (lights.h) as a colour, for scenes with transparent materials: each shadow
// ray's shadow_filter from `tnear` along it; an area light's mean over its whole grid of samples
// (not adaptively: the samples' colours need not agree where their visibility does).
Vec3 light_filter(const Scene& scene, const Light& l, const LightArrival& at, const Vec3& origin,
                  double tnear, double cone0, double cone, const Interiors& inside,
                  const EmbreeScene& rt, RayWork& shadow,
                  const std::atomic<bool>* cancel = nullptr);

}  // namespace softtrace

#include "render/shading.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/cancel.h"
#include "render/finish.h"
#include "render/lights.h"
#include "render/occlusion.h"
#include "render/transparency.h"
#include "scene/traced_objects.h"

namespace softtrace {

namespace {
// Transmitted rays through surfaces of ior 1 keep their trace level (POV-Ray's continued rays):
// at most this many in a row, so that no chain of them runs unbounded.
constexpr int kMaxContinued = 64;
thread_local int continued = 0;

// Counts one continued ray for as long as it is shaded (also when an EmbreeError leaves early).
class ContinuedRay {
 public:
  explicit ContinuedRay(bool counts) : counts_(counts) { continued += counts_; }
  ~ContinuedRay() { continued -= counts_; }
  ContinuedRay(const ContinuedRay&) = delete;
  ContinuedRay& operator=(const ContinuedRay&) = delete;

 private:
  const bool counts_;
};
// A field's components' values at the hit, and the weights of their materials: kept per thread
// (no allocation per pixel), and asked for only where the object has components (a
// thread_local's first-use check costs every call that names it).
std::vector<double>& component_terms() {
  thread_local std::vector<double> terms;
  return terms;
}
std::vector<ComponentMaterials::Weight>& component_weights() {
  thread_local std::vector<ComponentMaterials::Weight> weights;
  return weights;
}

// shade() at a point that is not shades_plain(): blended materials, mirrors, transparency, ambient
// occlusion. Out of line, so that the plain points (most of a frame's) do not pay for its frame
// and registers.
[[gnu::noinline]] Shaded shade_general(const Scene& scene, const SceneTracers& tracers,
                                       const EmbreeScene& rt, const Ray& ray, const TraceHit& hit,
                                       RayWork& secondary, const std::atomic<bool>* cancel,
                                       int level, double weight, const Interiors* interiors,
                                       ShadowListsOnDemand* shadow, const ObjectTracer* tracer,
                                       const SceneObject& obj, const Vec3& p) {
  // A field's gradient walk also gives its components' values, which weigh their materials below
  // (`terms`).
  const bool fused = obj.components && tracer && !hit.on_box_face;
  std::vector<double>* terms = nullptr;
  if (fused) {
    terms = &component_terms();
    terms->resize(size_t(obj.components->size()));
  }
  const Vec3 n = facing_normal(tracer, ray, hit, p, fused ? terms->data() : nullptr);
  // The interiors the ray travels in, which its shadow and mirror rays start in (POV-Ray's
  // interior list: only transmitted rays enter any, so in a scene without transparency it is
  // empty).
  static const Interiors kAir{};
  const Interiors& here = interiors ? *interiors : kAir;

  const double cone0 = footprint_at(ray, hit);
  // A primitive's hit is exact to rounding: its rays leave by the footprint, or by 1e-9 of the
  // coordinates' magnitude (an infinite plane's box says nothing of the scale). A mesh's is
  // Embree's float test: its rays leave as a field's do.
  const double offset = shadow ? shadow->offset() : ray_offset(obj, p, cone0);
  // Ambient occlusion's rays, and in scenes without transparency every ray, start that far along
  // the normal.
  const Vec3 lifted = p + n * offset;
  // In a scene with transparency the shadow, mirror and transmitted rays start at the hit itself
  // and ignore what lies nearer than `offset` along them (POV-Ray's way, docs/math.md §12.6): a
  // ray moved sideways by the footprint is moved again by every lens it passes through, so the
  // refracted views and the shadows seen through the glass would part from POV-Ray's by a pixel.
  const Vec3 origin = scene.transparent ? p : lifted;
  const double tnear = scene.transparent ? offset : 0;

  // A blend whose components carry materials: POV-Ray shades the point with each component's
  // material and sums the colours with weights |s_i f_i(p)|, normalised (docs/math.md, "Blended
  // materials"). One material with a non-zero weight is shaded as a plain object. The reflected
  // ray's shade() below reuses `weights` and `terms`: they are read only before that call.
  // An object without components (the common case) touches neither list.
  std::vector<ComponentMaterials::Weight>* weights = nullptr;
  if (obj.components) {
    weights = &component_weights();
    weights->clear();
    if (fused)
      obj.components->weights(terms->data(), *weights);
    else
      obj.components->weights(hit.face > 0 ? hit.face_point : p, *weights);
  }
  const bool blended = weights && weights->size() > 1;
  const Material& m = weights && weights->size() == 1
                          ? obj.components->materials()[(*weights)[0].material]
                          : obj.material;
  const auto each = [&](const auto& f) {
    for (const ComponentMaterials::Weight& w : *weights)
      f(obj.components->materials()[w.material], w.weight);
  };

  // `light` is what the pigment multiplies (ambient and diffuse, summed in the lights' order);
  // `shine` the highlights, which it does not. A blended point sums its materials' colours in
  // `mixed` instead.
  Vec3 light{0, 0, 0}, shine{0, 0, 0}, mixed{0, 0, 0};
  const AmbientOcclusion& occlusion = scene.image.occlusion;
  double open = -1;  // the open fraction of the sky, once traced
  for (size_t li = 0; li < scene.lights.size(); ++li) {
    const Light& l = scene.lights[li];
    if (cancel_requested(cancel)) break;  // up to 1,000 lights, each with its shadow rays
    if (l.type == Light::Type::Ambient) {
      // With ambient occlusion the ambient lights reach the point through its open sky, traced
      // once for all of them.
      if (occlusion.samples > 0 && open < 0)
        open = open_sky(occlusion, lifted, n, cone0, ray.cone, rt, secondary, cancel);
      const Vec3 c = open < 0 ? l.color * l.intensity : l.color * (l.intensity * open);
      if (!blended)
        light += mul(m.ambient, c);
      else
        each([&](const Material& mk, double wk) {
          mixed += mul(mk.color, mul(mk.ambient, c)) * (wk * opacity(mk));
        });
      continue;
    }
    LightArrival at;
    if (!light_arrival(l, p, origin, at)) continue;
    const double cosine = dot(n, at.to_light);
    if (cosine <= 0) continue;
    Vec3 arrived = at.light;
    if (!scene.transparent) {
      const double seen = light_visibility(l, at, origin, cone0, ray.cone, rt, secondary, cancel,
                                           shadow ? shadow->of(int(li)) : nullptr);
      if (seen == 0) continue;
      if (seen != 1) arrived = at.light * seen;
    } else {
      // Shadow rays pass transparent surfaces, tinted by each (docs/math.md §12.6).
      const Vec3 f =
          light_filter(scene, l, at, origin, tnear, cone0, ray.cone, here, rt, secondary, cancel);
      if (f.x == 0 && f.y == 0 && f.z == 0) continue;
      arrived = mul(at.light, f);
    }
    // As in POV-Ray, lights without shadows (its fill lights) make no highlights.
    if (!blended) {
      light += diffuse_light(m, cosine, arrived);
      if (l.shadows) shine += highlights(m, n, ray.d, at.to_light, arrived);
      continue;
    }
    each([&](const Material& mk, double wk) {
      Vec3 c = mul(mk.color, diffuse_light(mk, cosine, arrived)) * opacity(mk);
      if (l.shadows) c += highlights(mk, n, ray.d, at.to_light, arrived);
      mixed += c * wk;
    });
  }
  // The interior's index of refraction is the object's (POV-Ray's interior), whatever material
  // shows at the point. Which side is which comes from the ray's interior list, not from the
  // normal (POV-Ray's way): leaving the object, the light passes into the next interior out.
  const double ior = obj.material.ior;
  const double cos_i = -dot(ray.d, n);
  // The mirror reflection, weighed by Fresnel's reflectance where the material asks.
  const auto reflectivity = [&](const Material& mk) {
    if (!mk.fresnel) return mk.reflection;
    const double f = fresnel_reflectance(cos_i, fresnel_ratio(here, hit.object, ior));
    return mk.reflection * f + mk.reflection_min * (1 - f);
  };
  // What of the light behind passes (POV's filter colour), less what is reflected where energy
  // is conserved.
  const auto passing = [&](const Material& mk) {
    Vec3 f = transmitted_color(mk);
    if (mk.conserve_energy) f = mul(f, Vec3{1, 1, 1} - reflectivity(mk));
    return f;
  };
  Vec3 color = mixed;
  Vec3 albedo = m.color;
  // What each material sends on (docs/math.md §12.3): POV-Ray shades a blended point once per
  // texture, each tracing its own transmitted and mirror rays with its own weight, and sums the
  // colours with the textures' weights. The rays are the same for every material (one normal,
  // the object's interior), so each is traced once and shaded once per distinct ray weight.
  struct Onward {
    double weight;    // the material's share of the point (1 for a plain one)
    Vec3 reflection;  // its reflectivity
    Vec3 filter;      // what of the light behind passes it (see_through)
    bool see_through;
    bool total_reflection;  // its transmitted ray reflected whole: no mirror ray of its own
  };
  Onward single{1, reflectivity(m), {0, 0, 0}, false, false};
  std::vector<Onward> many;  // a blended point's, one per material
  if (!blended) {
    if (transparent(m)) {
      light = light * opacity(m);
      single.see_through = true;
      single.filter = passing(m);
    }
    color = mul(m.color, light);
    if (shine.x != 0 || shine.y != 0 || shine.z != 0) color += shine;
  } else {
    albedo = Vec3{0, 0, 0};
    many.reserve(weights->size());
    each([&](const Material& mk, double wk) {
      albedo += mk.color * wk;
      many.push_back({wk, reflectivity(mk), transparent(mk) ? passing(mk) : Vec3{0, 0, 0},
                      transparent(mk), false});
    });
  }
  // `weights` is read for the last time above: the rays below shade other points.
  Onward* const onward = blended ? many.data() : &single;
  const size_t materials = blended ? many.size() : 1;
  const bool deeper = level < scene.image.max_trace_level;
  // No transmitted or mirror ray to trace (an opaque matte point, or the deepest level): done,
  // before the rays' state below is set up.
  bool onward_rays = false;
  for (size_t k = 0; k < materials; ++k)
    onward_rays = onward_rays || onward[k].see_through || reflects(onward[k].reflection);
  if (!deeper || !onward_rays) return {color, n, albedo};

  // A ray's colour for each weight it is shaded with (the weight bounds the chain of rays below
  // it, docs/math.md §12.6, "Ray weights").
  struct Seen {
    double weight;
    Vec3 color;
  };
  const auto seen_with = [&](std::vector<Seen>& cache, double w, const auto& trace) {
    for (const Seen& c : cache)
      if (c.weight == w) return c.color;
    cache.push_back({w, trace(w)});
    return cache.back().color;
  };

  // The transmitted ray (POV-Ray traces it first), where enough light passes to matter: its grey
  // here, and its weight down the chain of rays.
  Crossing crossing;  // the transmitted ray's interiors and index ratio (transparency.h)
  int crossed = -1;   // -1: not yet tried; 0: no ray (too deep a list); 1: `next` holds it
  Ray next;
  int next_level = level + 1;
  const Interiors* inside = &crossing.next;
  bool total_reflection = false;
  TraceHit far;
  std::vector<Seen> transmitted;
  for (size_t k = 0; k < materials; ++k) {
    Onward& o = onward[k];
    const double transmitted_weight = weight * max_abs(o.filter);
    if (!o.see_through || !(std::min(1.0, std::abs(grey(o.filter))) > kAdcBailout) ||
        transmitted_weight < kAdcBailout || !deeper || cancel_requested(cancel))
      continue;
    if (crossed < 0) {
      crossed = cross(here, hit.object, ior, crossing) ? 1 : 0;
      const double eta = crossing.eta;  // n_incident / n_transmitted
      next = {p, ray.d, cone0, ray.cone};
      if (crossed && std::abs(eta - 1) < 1e-10) {
        next_level = level;  // a straight transmitted ray continues the ray
      } else if (crossed && !refract(ray.d, n, eta, next.d)) {
        // Total internal reflection: all of the light reflects, untinted, in the ray's interiors.
        total_reflection = true;
        next = {p, normalize(ray.d - n * (2 * dot(ray.d, n))), cone0, ray.cone};
        inside = &here;
      }
      if (crossed && (next_level > level || continued < kMaxContinued)) {
        far = rt.intersect(next, offset, std::numeric_limits<double>::infinity(), nullptr, *inside);
        secondary.add(far.work);
      } else {
        crossed = 0;
      }
    }
    if (!crossed) continue;
    o.total_reflection = total_reflection;
    const Vec3 seen = seen_with(transmitted, transmitted_weight, [&](double w) {
      const ContinuedRay count(next_level == level);
      return far.hit
                 ? shade(scene, tracers, rt, next, far, secondary, cancel, next_level, w, inside)
                       .color
             : scene.sky ? scene.sky->seen(next.d)
                         : scene.background;
    });
    color += (total_reflection ? seen : mul(o.filter, seen)) * o.weight;
  }

  // The mirror reflection (which total internal reflection has replaced), while its weight lasts.
  bool mirrored = false;
  Ray mirror;
  TraceHit bounced;
  std::vector<Seen> reflected;
  for (size_t k = 0; k < materials; ++k) {
    const Onward& o = onward[k];
    const double reflected_weight = weight * max_abs(o.reflection);
    if (o.total_reflection || !reflects(o.reflection) || reflected_weight < kAdcBailout ||
        !deeper || cancel_requested(cancel))
      continue;
    if (!mirrored) {
      mirrored = true;
      mirror = {origin, normalize(ray.d - n * (2 * dot(ray.d, n))), cone0, ray.cone};
      bounced = rt.intersect(mirror, tnear, std::numeric_limits<double>::infinity(), nullptr, here);
      secondary.add(bounced.work);
    }
    const Vec3 seen = seen_with(reflected, reflected_weight, [&](double w) {
      return bounced.hit ? shade(scene, tracers, rt, mirror, bounced, secondary, cancel, level + 1,
                                 w, &here)
                               .color
             : scene.sky ? scene.sky->seen(mirror.d)
                         : scene.background;
    });
    color += mul(o.reflection, seen) * o.weight;
  }
  return {color, n, albedo};
}
}  // namespace

Shaded shade(const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
             const TraceHit& hit, RayWork& secondary, const std::atomic<bool>* cancel, int level,
             double weight, const Interiors* interiors, ShadowListsOnDemand* shadow) {
  const ObjectTracer* tracer = tracers.tracer(hit.object);
  // A CSG's hit is on one of its operands: the face's material is that operand's.
  const SceneObject& obj =
      hit.face > 0 ? face_object(scene.objects[hit.object], hit.face) : scene.objects[hit.object];
  // With shadow lists, the point as ShadowBeams took it (the same arithmetic, its very bits).
  const Vec3 p = shadow ? shadow->p() : ray.o + ray.d * hit.t;
  if (!shades_plain(scene, obj))
    return shade_general(scene, tracers, rt, ray, hit, secondary, cancel, level, weight, interiors,
                         shadow, tracer, obj, p);
  // A plain point (no components, so no terms; no transparency, so its rays start at `lifted`)
  // is done by the short way.
  const Vec3 n = facing_normal(tracer, ray, hit, p, nullptr);
  const double cone0 = footprint_at(ray, hit);
  const Vec3 lifted = p + n * (shadow ? shadow->offset() : ray_offset(obj, p, cone0));
  return shade_plain(scene, rt, ray.d, p, n, lifted, cone0, ray.cone, obj.material, secondary,
                     cancel, shadow);
}

}  // namespace softtrace

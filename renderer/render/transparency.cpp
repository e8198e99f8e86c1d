#include "render/transparency.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "render/cancel.h"
#include "render/finish.h"
#include "render/point_hash.h"
#include "scene/traced_objects.h"

namespace softtrace {

namespace {
constexpr int kMaxSurfaces = 64;  // surfaces one shadow ray crosses before it counts as blocked
}  // namespace

double fresnel_reflectance(double cos_i, double ratio) {
  // The unpolarised Fresnel equations in Cook and Torrance's form ("A reflectance model for
  // computer graphics", 1982, eq. 8), as POV-Ray 3.7 evaluates them, with g^2 = ratio^2 + c^2 - 1.
  const double gg = ratio * ratio + cos_i * cos_i - 1;
  if (gg <= 0) return 1;  // past the critical angle
  const double g = std::sqrt(gg), c = cos_i;
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return std::clamp(0.5 * a * a * (1 + b * b), 0.0, 1.0);
}

bool refract(const Vec3& d, const Vec3& n, double eta, Vec3& out) {
  const double c = -dot(d, n);
  const double k = 1 + eta * eta * (c * c - 1);  // cos^2 of the refracted angle
  if (k < 0) return false;
  out = d * eta + n * (eta * c - std::sqrt(k));
  return true;
}

double leave_distance(const SceneObject& obj, const Vec3& p, double cone0) {
  return std::max(
      obj.field || obj.mesh ? 1e-4 * obj.bounds.diagonal() : 1e-9 * std::max(1.0, max_abs(p)),
      cone0);
}

Vec3 surface_transmission(const Scene& scene, const Ray& ray, const TraceHit& hit) {
  const SceneObject& obj = face_object(scene.objects[hit.object], hit.face);
  if (!obj.components) return transmitted_color(obj.material);
  thread_local std::vector<ComponentMaterials::Weight> weights;
  obj.components->weights(hit.face > 0 ? hit.face_point : ray.o + ray.d * hit.t, weights);
  if (weights.empty()) return transmitted_color(obj.material);
  Vec3 sum{0, 0, 0};
  for (const ComponentMaterials::Weight& w : weights)
    sum += transmitted_color(obj.components->materials()[w.material]) * w.weight;
  return sum;
}

Vec3 shadow_filter(const Scene& scene, const EmbreeScene& rt, const Ray& ray, double tnear,
                   double distance, const Interiors& inside, RayWork& shadow) {
  TraceCounters work;
  const auto count = [&](const TraceCounters& c) {
    work.point_evals += c.point_evals;
    work.box_evals += c.box_evals;
    work.refine_iterations += c.refine_iterations;
    work.give_ups += c.give_ups;
    work.undecided += c.undecided;
    work.entered_box = work.entered_box || c.entered_box;
  };
  Vec3 f{1, 1, 1};
  double t = tnear;
  Interiors in = inside;
  for (int k = 0;; ++k) {
    if (k == kMaxSurfaces) {
      f = {0, 0, 0};
      break;
    }
    const TraceHit h = rt.intersect(ray, t, distance, nullptr, in);
    count(h.work);
    if (!h.hit) break;
    f = mul(f, surface_transmission(scene, ray, h));
    if (f.x <= 0 && f.y <= 0 && f.z <= 0) {
      f = {0, 0, 0};
      break;
    }
    // Past the surface: out of the object's solid, or into it (POV-Ray's ComputeShadowMedia).
    if (!in.remove(h.object) && !in.push(h.object, 1)) {
      f = {0, 0, 0};
      break;
    }
    const Vec3 p = ray.o + ray.d * h.t;
    t = h.t + leave_distance(scene.objects[h.object], p, ray.cone_at(h.t));
    if (!(t < distance)) break;
  }
  shadow.add(work);
  return f;
}

bool cross(const Interiors& in, int object, double ior, Crossing& out) {
  out.next = in;
  if (in.empty()) {  // from the air
    out.eta = 1 / ior;
    return out.next.push(object, ior);
  }
  if (in.back().object == object) {  // out of the innermost, into the next one out or the air
    out.next.remove(object);
    out.eta = ior / (out.next.empty() ? 1 : out.next.back().ior);
    return true;
  }
  if (out.next.remove(object)) {  // out of an overlapped one: the overlap was the inner's
    out.eta = 1;
    return true;
  }
  out.eta = in.back().ior / ior;  // into it from the innermost
  return out.next.push(object, ior);
}

double fresnel_ratio(const Interiors& in, int object, double ior) {
  if (in.empty()) return ior;
  if (in.contains(object)) return in.size() == 1 ? 1 / ior : in.back().ior / ior;
  return ior / in.back().ior;
}

Vec3 light_filter(const Scene& scene, const Light& l, const LightArrival& at, const Vec3& origin,
                  double tnear, double cone0, double cone, const Interiors& inside,
                  const EmbreeScene& rt, RayWork& shadow, const std::atomic<bool>* cancel) {
  if (!l.shadows) return {1, 1, 1};
  if (!l.has_area)
    return shadow_filter(scene, rt, {origin, at.to_light, cone0, cone}, tnear, at.distance, inside,
                         shadow);
  const uint64_t seed = point_seed(origin);
  Vec3 sum{0, 0, 0};
  for (int i = 0; i < l.area.size1; ++i)
    for (int j = 0; j < l.area.size2; ++j) {
      if (cancel_requested(cancel)) return sum;  // moot once cancelled
      const Vec3 to = area_sample(l, seed, i, j) - origin;
      const double distance = length(to);
      sum += distance == 0 ? Vec3{1, 1, 1}
                           : shadow_filter(scene, rt, {origin, to / distance, cone0, cone}, tnear,
                                           distance, inside, shadow);
    }
  return sum * (1.0 / (l.area.size1 * l.area.size2));
}

}  // namespace softtrace

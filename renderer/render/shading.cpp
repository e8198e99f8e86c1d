#include "render/shading.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

Shaded shade(const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
             const TraceHit& hit, RayWork& shadow) {
  const ObjectTracer* tracer = tracers.tracer(hit.object);
  const SceneObject& obj = tracers.object(hit.object);
  const Vec3 p = ray.o + ray.d * hit.t;
  // A primitive's normal came with its exact hit.
  Vec3 n = !tracer ? hit.normal : hit.on_box_face ? tracer->box_face_normal(p) : tracer->normal(p);
  if (length(n) == 0) n = -ray.d;  // a flat spot of the field: face the viewer
  if (dot(n, ray.d) > 0) n = -n;   // seen from inside (clipped solids): shade the side we see

  // Shadow rays keep the camera ray's footprint: they decide what this pixel shows. They leave
  // the surface by that footprint's radius (at least 1e-4 of the object's box), far more than the
  // hit's error (1e-3 of it): nearer, the tracer would have to resolve the very surface it leaves.
  const double cone0 = ray.cone0 + ray.cone * hit.t;
  // A primitive's hit is exact to rounding: its rays leave by the footprint, or by 1e-9 of the
  // coordinates' magnitude (an infinite plane's box says nothing of the scale).
  const double offset =
      std::max(tracer ? 1e-4 * obj.bounds.diagonal() : 1e-9 * std::max(1.0, max_abs(p)), cone0);
  const Vec3 origin = p + n * offset;

  Vec3 light{0, 0, 0};
  for (const Light& l : scene.lights) {
    const Vec3 power = l.color * l.intensity;
    if (l.type == Light::Type::Ambient) {
      light += power;
      continue;
    }
    Vec3 to_light;
    double distance = std::numeric_limits<double>::infinity();
    if (l.type == Light::Type::Directional) {
      to_light = -l.direction;
    } else {
      const Vec3 v = l.position - origin;
      distance = length(v);
      if (distance == 0) continue;
      to_light = v / distance;
    }
    const double cosine = dot(n, to_light);
    if (cosine <= 0) continue;
    if (l.shadows) {
      TraceCounters work;
      const bool blocked = rt.occluded({origin, to_light, cone0, ray.cone}, 0, distance, work);
      shadow.add(work);
      if (blocked) continue;
    }
    light += power * cosine;
  }
  return {{obj.color.x * light.x, obj.color.y * light.y, obj.color.z * light.z}, n};
}

}  // namespace softtrace

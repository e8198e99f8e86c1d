// Lambertian shading of a hit from the field gradient, with shadow rays and ambient light.
#pragma once

#include "trace/embree_scene.h"
#include "trace/tracer.h"

namespace softtrace {

struct Shaded {
  Vec3 color;
  Vec3 normal;  // unit, facing the viewer
};

// The normal comes from the hit object's tracer; shadow rays go through `rt`, each one's work
// added to `shadow`.
Shaded shade(const Scene& scene, const SceneTracers& tracers, const EmbreeScene& rt, const Ray& ray,
             const TraceHit& hit, RayWork& shadow);

}  // namespace softtrace

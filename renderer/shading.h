// Lambertian shading of a hit from the field gradient, with shadow rays and ambient light.
#pragma once

#include "embree_scene.h"

namespace softtrace {

struct Shaded {
  Vec3 color;
  Vec3 normal;  // unit, facing the viewer
};

Shaded shade(const Scene& scene, const EmbreeScene& rt, const Ray& ray, const TraceHit& hit,
             int& steps);

}  // namespace softtrace

// A triangle mesh's hit (scene/triangle_mesh.h), once Embree's float test has found the triangle:
// the distance again in double (Moller-Trumbore on the same float vertices), so that shading
// starts its rays from the surface to double precision, and the normal.
#pragma once

#include <cstdint>

#include "scene/triangle_mesh.h"
#include "trace/tracer.h"

namespace softtrace {

struct MeshHit {
  double t = 0;
  Vec3 normal;  // unit: the file's normals interpolated (smooth), or the triangle's (flat)
};

// `triangle` hit by `ray` where Embree found t_float with barycentrics (u, v) (the point is
// (1 - u - v) v0 + u v1 + v v2). Where the double test misses (a hit on an edge, within
// rounding) or the triangle is degenerate, Embree's t and barycentrics stand.
MeshHit mesh_hit(const TriangleMesh& mesh, uint32_t triangle, const Ray& ray, double t_float,
                 double u, double v);

}  // namespace softtrace

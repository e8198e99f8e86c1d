#include "trace/mesh_hit.h"

#include <cmath>

#include "scene/ranges.h"

namespace softtrace {

MeshHit mesh_hit(const TriangleMesh& mesh, uint32_t triangle, const Ray& ray, double t_float,
                 double u, double v) {
  const uint32_t* idx = &mesh.indices[3 * size_t(triangle)];
  const Vec3 v0 = mesh.vertex(idx[0]), v1 = mesh.vertex(idx[1]), v2 = mesh.vertex(idx[2]);
  const Vec3 e1 = v1 - v0, e2 = v2 - v0;
  const Vec3 ng = cross(e1, e2);  // counter-clockwise seen from outside: outward
  MeshHit h;
  h.t = t_float;
  // Moller-Trumbore: p = o + t d = v0 + b1 e1 + b2 e2.
  const Vec3 pv = cross(ray.d, e2);
  const double det = dot(e1, pv);
  if (std::abs(det) > 0 && std::isfinite(det)) {
    const Vec3 s = ray.o - v0;
    const double b1 = dot(s, pv) / det;
    const Vec3 q = cross(s, e1);
    const double b2 = dot(ray.d, q) / det;
    const double t = dot(e2, q) / det;
    if (b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 && std::isfinite(t)) {
      h.t = t;
      u = b1;
      v = b2;
    }
  }
  Vec3 n{0, 0, 0};
  if (!mesh.normal_indices.empty()) {
    const uint32_t* ni = &mesh.normal_indices[3 * size_t(triangle)];
    n = mesh.normals[ni[0]] * (1 - u - v) + mesh.normals[ni[1]] * u + mesh.normals[ni[2]] * v;
  }
  if (!(max_abs(n) > 0)) n = ng;  // flat, or normals that cancel here
  h.normal = max_abs(n) > 0 ? unit(n) : Vec3{0, 0, 0};
  return h;
}

}  // namespace softtrace

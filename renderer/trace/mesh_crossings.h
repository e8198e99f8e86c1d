// A closed triangle mesh as a solid (a CSG operand: docs/scene-format.md "Triangle meshes"): every
// crossing of a ray with its triangles, in double precision over a bounding volume hierarchy of
// its own (Embree's float test finds only the nearest hit, and the tracer never sees Embree), and
// from them the stretches of the ray inside it.
//
// Inside is where the winding number is not zero (the nonzero rule): walking the ray from
// outside the mesh's box, each crossing of a triangle whose outward side faces the ray adds one,
// each of one that faces away takes one off. A closed, consistently oriented mesh (the loader
// refuses others: scene/mesh_closure.h) gives 1 inside a shell, 2 inside a shell nested in
// another, 0 in a hollow (a shell turned inward). A mesh whose triangles all face inward (a
// negative volume) is taken turned. Crossings within 1e-9 of the mesh's box of one another are
// one crossing with the sum of their signs clamped to one step: a ray through an edge or a
// vertex, which the triangles there all report (each triangle's test accepts rounding's worth
// beyond its edges, so no ray slips between two), crosses the surface once or touches it.
#pragma once

#include <memory>
#include <vector>

#include "scene/triangle_mesh.h"
#include "trace/tracer.h"

namespace softtrace {

// One crossing of the surface along a ray: at t, entering (+1) or leaving (-1) the solid, the
// outward unit normal there (the file's normals interpolated, or the triangle's).
struct MeshCrossing {
  double t;
  int step;
  Vec3 normal;
};

class MeshSolid {
 public:
  explicit MeshSolid(std::shared_ptr<const TriangleMesh> mesh);

  // Where `ray` is inside the solid: the crossings along the whole line through the mesh's box
  // that change the inside (entries and exits, alternating, an entry first), in order of t.
  void crossings(const Ray& ray, std::vector<MeshCrossing>& out) const;
  const Box& box() const { return box_; }

 private:
  struct Node {
    Box box;
    // A leaf: triangles [first, first + count) of order_; an inner node: count = 0, children
    // first and first + 1 of nodes_.
    uint32_t first = 0, count = 0;
  };
  void build(uint32_t node, uint32_t begin, uint32_t end, const std::vector<Vec3>& centroids);
  void hits(const Ray& ray, double t0, double t1, std::vector<MeshCrossing>& out) const;

  std::shared_ptr<const TriangleMesh> mesh_;
  double orientation_ = 1;  // -1: the triangles face inward; every side turns
  double merge_ = 0;        // crossings closer than this are one
  Box box_;
  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;
};

}  // namespace softtrace

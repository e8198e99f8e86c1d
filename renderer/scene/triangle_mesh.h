// A triangle mesh object (docs/scene-format.md "mesh"): a mesh file's triangles, placed in the
// world. The renderer hands them to Embree as its own triangle geometry; a hit's normal is the
// triangle's, or with the file's normals the interpolated one (trace/mesh_hit.h). Plain data: the
// tracer includes this, never the loader (mesh_load.h).
#pragma once

#include <cstdint>
#include <vector>

#include "math/box.h"
#include "math/vec.h"

namespace softtrace {

struct TriangleMesh {
  // World space, as Embree takes them: x, y, z per vertex (float: what is intersected is this),
  // and three vertex indices per triangle.
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  // Smooth shading: unit normals (world space; zero where the file's was) and three indices into
  // them per triangle. Both empty: flat.
  std::vector<Vec3> normals;
  std::vector<uint32_t> normal_indices;
  Box world_box;
  size_t triangles() const { return indices.size() / 3; }
  Vec3 vertex(uint32_t i) const {
    return {positions[3 * size_t(i)], positions[3 * size_t(i) + 1], positions[3 * size_t(i) + 2]};
  }
};

}  // namespace softtrace

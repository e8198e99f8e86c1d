// The properties a mesh from fieldlib's mesher promises (mesh/mesh.h), checked from the faces
// alone: what a slicer or a game engine would check before accepting it.
#pragma once

#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace softtrace::mesh_check {

struct Report {
  long boundary_edges = 0;     // directed edge (a, b) with no (b, a)
  long nonmanifold_edges = 0;  // an undirected edge in more than two faces
  long misoriented_edges = 0;  // (a, b) used twice in the same direction
  long degenerate_faces = 0;   // area <= 1e-12 voxel^2, or a repeated vertex
  long components = 0;
  long odd_euler = 0;         // closed components whose V - E + F is odd
  std::vector<long> euler;    // V - E + F per component
  std::string first_problem;  // empty when all is well
};

Report check(const Mesh& m);

}  // namespace softtrace::mesh_check

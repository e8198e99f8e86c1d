// Whether a triangle mesh bounds a solid, as a CSG operand must (docs/scene-format.md "Triangle
// meshes"): closed and consistently oriented, every edge shared by exactly two triangles that run
// along it in opposite directions. Vertices at the same (placed) position are one vertex, so a
// file that repeats its corners per face (as STL-like exports do) is closed too.
#pragma once

#include <string>

#include "scene/triangle_mesh.h"

namespace softtrace {

// Empty when `mesh` is closed and consistently oriented; otherwise what is wrong, naming an edge
// by its vertices counted from 1 in the file: "its edge from vertex 3 to vertex 7 borders one
// triangle only (the mesh is open)". Triangles whose corners coincide bound nothing and are left
// out.
std::string mesh_closure_problem(const TriangleMesh& mesh);

}  // namespace softtrace

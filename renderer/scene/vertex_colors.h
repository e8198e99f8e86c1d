// Mesh vertex colours from an object's materials (docs/mesh.md "Colour"): the object's pigment,
// or, where its field's components carry their own materials, the colours mixed with POV-Ray's
// blob texture weights |s_i f_i(p)| / Σ_j |s_j f_j(p)| (component_materials.h), as the renderer
// shades that point.
#pragma once

#include <vector>

#include "math/vec.h"
#include "mesh/mesh_array.h"
#include "scene/scene.h"

namespace softtrace {

// One linear RGB colour per vertex of `vertices`, on `threads` threads (each vertex's colour
// depends on its position alone, so the result is the same for any thread count).
MeshArray<Vec3> vertex_colors(const SceneObject& obj, const MeshArray<Vec3>& vertices, int threads);

}  // namespace softtrace

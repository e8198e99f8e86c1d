// Reading a triangle mesh object (scene/triangle_mesh.h) from the scene file: kept apart from the
// struct, so that the tracer, which includes triangle_mesh.h, never compiles the JSON behind
// Params.
#pragma once

#include <memory>

#include "describe/params.h"
#include "scene/affine.h"
#include "scene/triangle_mesh.h"

namespace softtrace {

// Reads the object's "mesh" (a path, relative to the scene file's folder) and places it by
// `placement`. Throws SceneError: the mesh file's own located line (mesh_read.h) followed by the
// key's pointer, or the pointer of a placement that takes the mesh beyond kMaxPosition.
std::shared_ptr<const TriangleMesh> load_mesh(const Params& object, const Affine& placement);

}  // namespace softtrace

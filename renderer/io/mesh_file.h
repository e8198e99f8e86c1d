// Mesh files from fieldlib's mesher (mesh/mesh.h), written all or nothing (output_file.h):
// - .stl binary STL: positions and face normals (float), no colour;
// - .obj Wavefront OBJ: shared vertices ("v"), vertex normals ("vn"), faces "f a//a b//b c//c";
// - .ply binary little-endian PLY: float position and normal, 8-bit sRGB colour per vertex;
// - .glb glTF 2.0 binary: one mesh with POSITION, NORMAL, COLOR_0 (linear float RGB) and
//   16-bit indices up to 65,535 vertices, 32-bit past that. glTF's +Y is up and softtrace's +Z
//   is: a point (x, y, z) is written as (x, z, -y), the rotation by -90 degrees about x (winding
//   and handedness kept). STL, OBJ and PLY keep softtrace's frame (z up), as slicers expect.
// Positions and normals are written as 32-bit floats (OBJ: 9 significant digits).
#pragma once

#include <cstdio>
#include <string>

#include "mesh/mesh.h"

namespace softtrace {

enum class MeshFormat { Stl, Obj, Ply, Glb };

// The lower-case extensions the writer knows, nullptr-terminated (check_output_path's list).
extern const char* const kMeshExtensions[];

// The format an output path names; throws std::invalid_argument for another extension.
MeshFormat mesh_format(const std::string& path);

// Writes `m` to `path`: to a temporary file beside it, renamed over it once complete. Throws
// std::runtime_error naming the path; nothing is left behind then.
void write_mesh(const std::string& path, const Mesh& m);

// The formats' writers, on an open binary stream; each throws std::runtime_error when a write
// fails (mesh_stl.cpp, mesh_obj.cpp, mesh_ply.cpp, mesh_glb.cpp).
void write_stl(std::FILE* out, const Mesh& m);
void write_obj(std::FILE* out, const Mesh& m);
void write_ply(std::FILE* out, const Mesh& m);
void write_glb(std::FILE* out, const Mesh& m);

}  // namespace softtrace

// Reading triangle meshes (Wavefront OBJ, PLY) for the scene's "mesh" objects. A small reader of
// our own: Debian's tinyobjloader reads "v nan 0 0" and "v 1 x 0" as zeros and reports an index
// out of range only as a warning, and a hostile file must be refused at its line.
// - .obj: "v x y z" (a fourth to seventh number, w or a colour, is read and ignored), "vn x y z",
//   "f" with 1-based or negative (relative) indices "v", "v/vt", "v//vn", "v/vt/vn"; a polygon is
//   split into a fan of triangles. vt, vp, g, o, s, mg, usemtl, mtllib, l, p, lod, bevel,
//   c_interp, d_interp, maplib, usemap, shadow_obj and trace_obj lines are skipped; free-form
//   geometry (cstype, curv, surf, ...) and any other statement are refused.
// - .ply: ascii, binary_little_endian or binary_big_endian 1.0; the element "vertex" with
//   properties x, y, z (and nx, ny, nz together: vertex normals), the element "face" with a list
//   "vertex_indices" (or "vertex_index"), polygons as fans; every other element and property is
//   read past.
// Every error is one line that starts with the place: "path:LINE: ..." (a text line), or "path:
// vertex N: ..." / "path: face N: ..." in a binary body. Coordinates and normals must be finite
// (a file's "nan" is refused), indices within the vertices, counts within kMaxMeshVertices and
// kMaxMeshTriangles, the file within kMaxMeshFileBytes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/vec.h"

namespace softtrace {

constexpr size_t kMaxMeshVertices = size_t(1) << 24;
constexpr size_t kMaxMeshTriangles = size_t(1) << 24;
constexpr size_t kMaxMeshFileBytes = size_t(1) << 30;

struct MeshData {
  std::vector<Vec3> positions;
  std::vector<std::array<uint32_t, 3>> faces;  // into positions, in the file's winding
  // Normals for smooth shading: per face, its corners' indices into `normals` (OBJ "v//vn", a
  // PLY's per-vertex normals). Empty where the file gives none for some face: the mesh is flat.
  std::vector<Vec3> normals;
  std::vector<std::array<uint32_t, 3>> face_normals;
};

// A file that cannot be read as a mesh; what() is the located line.
struct MeshReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads `path` by its extension (.obj or .ply, any case). Throws MeshReadError.
MeshData read_mesh(const std::string& path);

// The readers, on the file's bytes; `name` is the path errors name (mesh_read_obj.cpp,
// mesh_read_ply.cpp).
MeshData read_obj(const std::string& bytes, const std::string& name);
MeshData read_ply(const std::string& bytes, const std::string& name);

}  // namespace softtrace

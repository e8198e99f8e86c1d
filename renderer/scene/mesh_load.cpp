#include "scene/mesh_load.h"

#include <cmath>
#include <filesystem>

#include "io/mesh_read.h"
#include "scene/placement.h"
#include "scene/ranges.h"

namespace softtrace {

std::shared_ptr<const TriangleMesh> load_mesh(const Params& p, const Affine& placement) {
  const std::string name = p.string("mesh");
  p.check(!name.empty(), "mesh", "expected the path of an .obj or .ply file");
  // Relative to the scene file, so that a scene and its meshes move together.
  const std::filesystem::path file(name);
  const std::string path =
      file.is_absolute() ? name : (std::filesystem::path(*p.file()).parent_path() / file).string();
  MeshData data;
  try {
    data = read_mesh(path);
  } catch (const MeshReadError& e) {
    throw SceneError(std::string(e.what()) + " (read for " + p.where("mesh") + ")");
  }
  Mat3 to_object;
  p.check(invert(placement.linear, to_object), "",
          "expected an invertible placement (scale and matrix)");
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions.reserve(3 * data.positions.size());
  for (size_t i = 0; i < data.positions.size(); ++i) {
    const Vec3 w = placement.apply(data.positions[i]);
    if (!(max_abs(w) <= kMaxPosition))
      p.fail("mesh", path + ": vertex " + std::to_string(i + 1) + " is placed beyond 1e12 " +
                         "of the origin (expected every vertex " + kPositionRule + ")");
    mesh->world_box.extend(w);
    for (int k = 0; k < 3; ++k) mesh->positions.push_back(static_cast<float>(w[k]));
  }
  mesh->indices.reserve(3 * data.faces.size());
  for (const auto& f : data.faces) mesh->indices.insert(mesh->indices.end(), f.begin(), f.end());
  if (!data.face_normals.empty()) {
    // Normals are covectors: they go through the inverse transpose.
    mesh->normals.reserve(data.normals.size());
    for (const Vec3& n : data.normals) {
      const Vec3 w = to_object.transposed_times(n);
      mesh->normals.push_back(max_abs(w) > 0 && std::isfinite(max_abs(w)) ? unit(w) : Vec3{});
    }
    mesh->normal_indices.reserve(3 * data.face_normals.size());
    for (const auto& f : data.face_normals)
      mesh->normal_indices.insert(mesh->normal_indices.end(), f.begin(), f.end());
  }
  return mesh;
}

}  // namespace softtrace

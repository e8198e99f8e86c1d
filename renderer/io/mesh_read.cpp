#include "io/mesh_read.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "io/file_read.h"

namespace softtrace {

MeshData read_mesh(const std::string& path) {
  std::string bytes, ext;
  try {
    refuse_nul_in_path(path);
    ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".obj" && ext != ".ply")
      throw MeshReadError(path + ": unknown mesh format '" + ext + "' (expected .obj or .ply)");
    bytes = read_file_bounded(path, kMaxMeshFileBytes, "mesh", AtNul::ReadOn);
  } catch (const FileReadError& e) {
    throw MeshReadError(e.what());
  }
  return ext == ".obj" ? read_obj(bytes, path) : read_ply(bytes, path);
}

}  // namespace softtrace

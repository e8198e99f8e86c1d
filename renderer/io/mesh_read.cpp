#include "io/mesh_read.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

namespace softtrace {

MeshData read_mesh(const std::string& path) {
  if (path.find('\0') != std::string::npos)
    throw MeshReadError(path.substr(0, path.find('\0')) + "...: a path with a NUL byte");
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".obj" && ext != ".ply")
    throw MeshReadError(path + ": unknown mesh format '" + ext + "' (expected .obj or .ply)");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw MeshReadError(path + ": is a folder, not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshReadError(path + ": cannot open the mesh file");
  // In blocks, so that an endless input (/dev/zero, a pipe) stops at the size limit.
  std::string bytes;
  std::vector<char> block(1 << 16);
  while (in) {
    in.read(block.data(), std::streamsize(block.size()));
    bytes.append(block.data(), size_t(in.gcount()));
    if (bytes.size() > kMaxMeshFileBytes)
      throw MeshReadError(path + ": larger than " + std::to_string(kMaxMeshFileBytes >> 20) +
                          " MiB; a mesh file may be at most that");
  }
  if (in.bad()) throw MeshReadError(path + ": cannot read the mesh file");
  return ext == ".obj" ? read_obj(bytes, path) : read_ply(bytes, path);
}

}  // namespace softtrace

// Binary little-endian PLY: per vertex float x y z nx ny nz and uchar red green blue (the
// linear colour encoded as sRGB, as viewers display PLY colours), per face a uchar count (3) and
// three int indices.
#include <algorithm>
#include <cmath>
#include <string>

#include "io/mesh_bytes.h"
#include "io/mesh_file.h"

namespace softtrace {
namespace {

uint8_t srgb8(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  return uint8_t(std::lround(s * 255));
}

}  // namespace

void write_ply(std::FILE* out, const Mesh& m) {
  using namespace mesh_bytes;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment softtrace mesh (z up)\nelement vertex " +
      std::to_string(m.vertices.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
      "property float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nelement face " +
      std::to_string(m.faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  put(out, header.data(), header.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    unsigned char record[27];
    const float data[6] = {float(m.vertices[i].x), float(m.vertices[i].y), float(m.vertices[i].z),
                           float(m.normals[i].x),  float(m.normals[i].y),  float(m.normals[i].z)};
    std::memcpy(record, data, sizeof data);
    for (int k = 0; k < 3; ++k) record[24 + k] = srgb8(m.colors[i][k]);
    put(out, record, sizeof record);
  }
  for (const auto& f : m.faces) {
    unsigned char record[13];
    record[0] = 3;
    const int32_t idx[3] = {int32_t(f[0]), int32_t(f[1]), int32_t(f[2])};
    std::memcpy(record + 1, idx, sizeof idx);
    put(out, record, sizeof record);
  }
}

}  // namespace softtrace

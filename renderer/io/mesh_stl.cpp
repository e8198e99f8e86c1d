// Binary STL: an 80-byte header, the face count, then per face its unit normal, three corners
// (32-bit floats) and a zero attribute word.
#include <cstring>

#include "io/mesh_bytes.h"
#include "io/mesh_file.h"

namespace softtrace {

void write_stl(std::FILE* out, const Mesh& m) {
  using namespace mesh_bytes;
  char header[80] = {};
  std::strncpy(header, "softtrace mesh (binary STL, z up)", sizeof header - 1);
  put(out, header, sizeof header);
  put_value(out, uint32_t(m.faces.size()));
  for (const auto& f : m.faces) {
    const Vec3 a = m.vertices[f[0]], b = m.vertices[f[1]], c = m.vertices[f[2]];
    const Vec3 n = cross(b - a, c - a);
    const double len = length(n);
    const Vec3 unit = len > 0 ? n / len : Vec3{};
    float data[12];
    const Vec3* v[4] = {&unit, &a, &b, &c};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) data[3 * i + k] = float((*v[i])[k]);
    put(out, data, sizeof data);
    put_value(out, uint16_t(0));
  }
}

}  // namespace softtrace

// Wavefront OBJ: "v" and "vn" lines in the same order (vertex i has normal i), faces with
// 1-based indices "f a//a b//b c//c".
#include <cinttypes>

#include "io/mesh_bytes.h"
#include "io/mesh_file.h"

namespace softtrace {

void write_obj(std::FILE* out, const Mesh& m) {
  auto check = [](int n) {
    if (n < 0) throw std::runtime_error("write failed (disk full?)");
  };
  check(std::fprintf(out, "# softtrace mesh: %zu vertices, %zu faces (z up)\n", m.vertices.size(),
                     m.faces.size()));
  for (const Vec3& v : m.vertices) check(std::fprintf(out, "v %.9g %.9g %.9g\n", v.x, v.y, v.z));
  for (const Vec3& n : m.normals) check(std::fprintf(out, "vn %.7g %.7g %.7g\n", n.x, n.y, n.z));
  for (const auto& f : m.faces) {
    const uint64_t a = f[0] + uint64_t(1), b = f[1] + uint64_t(1), c = f[2] + uint64_t(1);
    check(std::fprintf(
        out, "f %" PRIu64 "//%" PRIu64 " %" PRIu64 "//%" PRIu64 " %" PRIu64 "//%" PRIu64 "\n", a, a,
        b, b, c, c));
  }
}

}  // namespace softtrace

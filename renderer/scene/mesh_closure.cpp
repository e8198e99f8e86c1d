#include "scene/mesh_closure.h"

#include <algorithm>
#include <array>
#include <map>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace softtrace {

std::string mesh_closure_problem(const TriangleMesh& mesh) {
  if (mesh.triangles() == 0) return "it has no triangles, so no inside";
  // Each vertex as the first in the file at its position.
  const size_t n = mesh.positions.size() / 3;
  std::map<std::array<float, 3>, uint32_t> first;
  std::vector<uint32_t> weld(n);
  for (size_t i = 0; i < n; ++i) {
    const std::array<float, 3> p{mesh.positions[3 * i], mesh.positions[3 * i + 1],
                                 mesh.positions[3 * i + 2]};
    weld[i] = first.emplace(p, uint32_t(i)).first->second;
  }
  // How many triangles run along each edge, per direction (key: the edge from a to b, a < b).
  struct Uses {
    int forward = 0, backward = 0;
  };
  std::unordered_map<uint64_t, Uses> edges;
  edges.reserve(3 * mesh.triangles());
  for (size_t t = 0; t < mesh.triangles(); ++t) {
    const uint32_t v[3] = {weld[mesh.indices[3 * t]], weld[mesh.indices[3 * t + 1]],
                           weld[mesh.indices[3 * t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      Uses& u = edges[uint64_t(std::min(a, b)) << 32 | std::max(a, b)];
      (a < b ? u.forward : u.backward)++;
    }
  }
  if (edges.empty()) return "its triangles have no area, so no inside";
  // The first bad edge in vertex order, so the message is the same on every run.
  std::vector<std::pair<uint64_t, Uses>> bad;
  for (const auto& [key, u] : edges)
    if (u.forward != 1 || u.backward != 1) bad.emplace_back(key, u);
  if (bad.empty()) return "";
  const auto& [key, u] = *std::min_element(
      bad.begin(), bad.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  const std::string edge = "its edge from vertex " + std::to_string((key >> 32) + 1) +
                           " to vertex " + std::to_string((key & 0xffffffffu) + 1);
  const int uses = u.forward + u.backward;
  if (uses == 1) return edge + " borders one triangle only (the mesh is open)";
  if (uses > 2)
    return edge + " borders " + std::to_string(uses) + " triangles (the mesh is not a manifold)";
  return edge +
         " is run along the same way by both its triangles (they face opposite sides: "
         "the mesh is not consistently oriented)";
}

}  // namespace softtrace

#include "mesh_check.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>

namespace softtrace::mesh_check {
namespace {

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  uint32_t find(uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

}  // namespace

Report check(const Mesh& m) {
  Report r;
  auto note = [&](const std::string& what) {
    if (r.first_problem.empty()) r.first_problem = what;
  };
  // Directed edges, sorted: each (a, b) must appear once, and (b, a) once.
  std::vector<std::pair<uint32_t, uint32_t>> directed;
  directed.reserve(m.faces.size() * 3);
  const double tiny = 1e-12 * m.voxel * m.voxel;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const auto& t = m.faces[f];
    for (int e = 0; e < 3; ++e) directed.emplace_back(t[e], t[(e + 1) % 3]);
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || 0.5 * length(cross(b - a, c - a)) <= tiny) {
      ++r.degenerate_faces;
      note("degenerate face " + std::to_string(f));
    }
  }
  std::sort(directed.begin(), directed.end());
  for (size_t i = 0; i < directed.size(); ++i) {
    if (i > 0 && directed[i] == directed[i - 1]) {
      ++r.misoriented_edges;
      note("edge used twice in one direction");
    }
    const std::pair<uint32_t, uint32_t> back{directed[i].second, directed[i].first};
    const auto range = std::equal_range(directed.begin(), directed.end(), back);
    if (range.first == range.second) {
      ++r.boundary_edges;
      note("boundary edge");
    } else if (range.second - range.first > 1) {
      ++r.nonmanifold_edges;
      note("edge in more than two faces");
    }
  }
  // Components (by shared vertices) and V - E + F of each.
  UnionFind uf(m.vertices.size());
  for (const auto& t : m.faces) {
    uf.unite(t[0], t[1]);
    uf.unite(t[1], t[2]);
  }
  std::vector<long> v(m.vertices.size(), 0), e(m.vertices.size(), 0), f(m.vertices.size(), 0);
  std::vector<uint8_t> used(m.vertices.size(), 0);
  for (const auto& t : m.faces) {
    ++f[uf.find(t[0])];
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
  }
  for (size_t i = 0; i < m.vertices.size(); ++i) v[uf.find(uint32_t(i))] += used[i];
  for (const auto& d : directed)
    if (d.first < d.second) ++e[uf.find(d.first)];
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    if (uf.find(uint32_t(i)) != i || !used[i]) continue;
    ++r.components;
    const long chi = v[i] - e[i] + f[i];
    r.euler.push_back(chi);
    if (chi % 2 != 0) {
      ++r.odd_euler;
      note("a component with odd Euler characteristic " + std::to_string(chi));
    }
  }
  return r;
}

}  // namespace softtrace::mesh_check

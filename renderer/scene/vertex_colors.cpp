#include "scene/vertex_colors.h"

#include <algorithm>
#include <thread>

#include "scene/component_materials.h"

namespace softtrace {

namespace {

// The pigment the renderer's shade() uses at p: one material's colour where one component's
// weight is non-zero, the weighted sum where several are, the object's where none is.
Vec3 mixed_color(const SceneObject& obj, const Vec3& p,
                 std::vector<ComponentMaterials::Weight>& weights) {
  obj.components->weights(p, weights);
  if (weights.empty()) return obj.material.color;
  Vec3 c{0, 0, 0};
  for (const ComponentMaterials::Weight& w : weights)
    c += obj.components->materials()[w.material].color * w.weight;
  return c;
}

}  // namespace

MeshArray<Vec3> vertex_colors(const SceneObject& obj, const MeshArray<Vec3>& vertices,
                              int threads) {
  MeshArray<Vec3> colors(vertices.size(), obj.material.color);
  if (!obj.components) return colors;
  // Contiguous slices, one per thread: each writes only its own vertices' colours.
  const size_t parts = size_t(std::max(threads, 1));
  const size_t slice = (vertices.size() + parts - 1) / parts;
  auto work = [&](size_t t) {
    std::vector<ComponentMaterials::Weight> weights;
    const size_t end = std::min(vertices.size(), (t + 1) * slice);
    for (size_t v = t * slice; v < end; ++v) colors[v] = mixed_color(obj, vertices[v], weights);
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < parts && t * slice < vertices.size(); ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& t : pool) t.join();
  return colors;
}

}  // namespace softtrace

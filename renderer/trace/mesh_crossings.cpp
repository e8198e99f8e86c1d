#include "trace/mesh_crossings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "scene/ranges.h"

namespace softtrace {

namespace {
constexpr uint32_t kLeafTriangles = 4;

// The ray's frame for the watertight test (Woop, Benthin and Wald 2013, "Watertight Ray/Triangle
// Intersection"): z the direction's largest component, x and y the next two in cyclic order
// (swapped when the direction's z is negative, to keep the winding), and the shear that takes the
// direction to z.
struct RayFrame {
  int kx, ky, kz;
  double sx, sy, sz;
  explicit RayFrame(const Vec3& d) {
    kz = std::abs(d.x) >= std::abs(d.y) ? (std::abs(d.x) >= std::abs(d.z) ? 0 : 2)
                                        : (std::abs(d.y) >= std::abs(d.z) ? 1 : 2);
    kx = (kz + 1) % 3;
    ky = (kx + 1) % 3;
    if (d[kz] < 0) std::swap(kx, ky);
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1 / d[kz];
  }
};

// The edge function of a and b seen along the ray: a triangle's two neighbours compute it from
// the same two sheared vertices with the operands swapped, so it is exactly negated there (no
// FMA contraction: the build uses no -march) and a ray through the shared edge hits exactly one
// of them, or both where it is exactly zero.
double edge(double ax, double ay, double bx, double by) {
  return ax * by - ay * bx;
}
}  // namespace

MeshSolid::MeshSolid(std::shared_ptr<const TriangleMesh> mesh) : mesh_(std::move(mesh)) {
  const TriangleMesh& m = *mesh_;
  box_ = m.world_box;
  merge_ = 1e-9 * box_.diagonal();
  // The solid's volume, six times over, about the box's centre: negative when the triangles
  // face inward.
  const Vec3 c = box_.center();
  double volume = 0;
  for (size_t i = 0; i < m.triangles(); ++i) {
    const uint32_t* t = &m.indices[3 * i];
    volume += dot(m.vertex(t[0]) - c, cross(m.vertex(t[1]) - c, m.vertex(t[2]) - c));
  }
  orientation_ = volume < 0 ? -1 : 1;
  const uint32_t n = static_cast<uint32_t>(m.triangles());
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  std::vector<Vec3> centroids(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t* t = &m.indices[3 * size_t(i)];
    centroids[i] = (m.vertex(t[0]) + m.vertex(t[1]) + m.vertex(t[2])) / 3.0;
  }
  nodes_.reserve(2 * size_t(n) / kLeafTriangles + 2);
  nodes_.emplace_back();
  if (n > 0) build(0, 0, n, centroids);
}

// Node `node` over order_[begin, end): a leaf of a few triangles, or split at the median of the
// centroids along their widest axis.
void MeshSolid::build(uint32_t node, uint32_t begin, uint32_t end,
                      const std::vector<Vec3>& centroids) {
  const TriangleMesh& m = *mesh_;
  Box box, spread;
  for (uint32_t i = begin; i < end; ++i) {
    const uint32_t* t = &m.indices[3 * size_t(order_[i])];
    for (int k = 0; k < 3; ++k) box.extend(m.vertex(t[k]));
    spread.extend(centroids[order_[i]]);
  }
  // Widened by the merging distance: a ray along a face of the box still reaches its triangles.
  const Vec3 pad{merge_, merge_, merge_};
  nodes_[node].box = Box(box.lo - pad, box.hi + pad);
  if (end - begin <= kLeafTriangles) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    return;
  }
  const Vec3 e = spread.extent();
  const int axis = e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
  const uint32_t mid = begin + (end - begin) / 2;
  // Ties broken by the index: the tree, and so the order of equal crossings, is the same on
  // every run.
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](uint32_t a, uint32_t b) {
                     const double ca = centroids[a][axis], cb = centroids[b][axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  const uint32_t left = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[node].first = left;
  nodes_[node].count = 0;
  build(left, begin, mid, centroids);
  build(left + 1, mid, end, centroids);
}

// Every triangle crossing along the ray within [t0, t1], in any order.
void MeshSolid::hits(const Ray& ray, double t0, double t1, std::vector<MeshCrossing>& out) const {
  const TriangleMesh& m = *mesh_;
  const RayFrame f(ray.d);
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    double a = t0, b = t1;
    if (!clip_to_box(ray, node.box, a, b)) continue;
    if (node.count == 0) {
      stack[top++] = node.first;
      stack[top++] = node.first + 1;
      continue;
    }
    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
      const uint32_t tri = order_[i];
      const uint32_t* idx = &m.indices[3 * size_t(tri)];
      const Vec3 pa = m.vertex(idx[0]) - ray.o, pb = m.vertex(idx[1]) - ray.o,
                 pc = m.vertex(idx[2]) - ray.o;
      const double ax = pa[f.kx] - f.sx * pa[f.kz], ay = pa[f.ky] - f.sy * pa[f.kz];
      const double bx = pb[f.kx] - f.sx * pb[f.kz], by = pb[f.ky] - f.sy * pb[f.kz];
      const double cx = pc[f.kx] - f.sx * pc[f.kz], cy = pc[f.ky] - f.sy * pc[f.kz];
      const double u = edge(cx, cy, bx, by), v = edge(ax, ay, cx, cy), w = edge(bx, by, ax, ay);
      if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) continue;
      const double det = u + v + w;
      if (det == 0 || !std::isfinite(det)) continue;  // seen edge on: no crossing
      const double t = (u * f.sz * pa[f.kz] + v * f.sz * pb[f.kz] + w * f.sz * pc[f.kz]) / det;
      if (!(t >= t0 && t <= t1)) continue;
      // det > 0: the triangle's counter-clockwise side, its outward one, faces the ray.
      MeshCrossing c{t, det > 0 ? 1 : -1, {}};
      Vec3 n{0, 0, 0};
      if (!m.normal_indices.empty()) {
        const uint32_t* ni = &m.normal_indices[3 * size_t(tri)];
        n = (m.normals[ni[0]] * u + m.normals[ni[1]] * v + m.normals[ni[2]] * w) / det;
      }
      if (!(max_abs(n) > 0)) n = cross(pb - pa, pc - pa);
      c.normal = max_abs(n) > 0 ? unit(n) * orientation_ : Vec3{0, 0, 0};
      c.step = orientation_ > 0 ? c.step : -c.step;
      out.push_back(c);
    }
  }
}

void MeshSolid::crossings(const Ray& ray, std::vector<MeshCrossing>& out) const {
  out.clear();
  if (mesh_->triangles() == 0) return;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double t0 = -kInf, t1 = kInf;
  if (!clip_to_box(ray, nodes_[0].box, t0, t1)) return;
  thread_local std::vector<MeshCrossing> all;
  all.clear();
  hits(ray, t0, t1, all);
  // Sorted by t, equal ones by step and normal, so the result does not depend on the tree's
  // order of visit.
  std::sort(all.begin(), all.end(), [](const MeshCrossing& a, const MeshCrossing& b) {
    if (a.t != b.t) return a.t < b.t;
    if (a.step != b.step) return a.step > b.step;
    if (a.normal.x != b.normal.x) return a.normal.x < b.normal.x;
    if (a.normal.y != b.normal.y) return a.normal.y < b.normal.y;
    return a.normal.z < b.normal.z;
  });
  int winding = 0;
  for (size_t i = 0; i < all.size();) {
    // One crossing of the surface: those within merge_ of the first, their steps summed and
    // clamped to one (an edge's two triangles, a vertex's fan); a sum of 0 only touches it.
    size_t j = i;
    int sum = 0;
    while (j < all.size() && all[j].t - all[i].t <= merge_) sum += all[j++].step;
    const int step = sum > 0 ? 1 : sum < 0 ? -1 : 0;
    const int before = winding;
    winding += step;
    // The normal of a triangle of the group that steps the way the group does.
    Vec3 normal = all[i].normal;
    for (size_t k = i; k < j; ++k)
      if (all[k].step == step) {
        normal = all[k].normal;
        break;
      }
    // The solid is where the winding is not zero: entered where it leaves 0, left where it comes
    // back. Past a region of winding -1 (triangles facing the other way) its outside is the
    // triangles' inside.
    if ((before == 0) != (winding == 0)) {
      const int change = before == 0 ? 1 : -1;
      out.push_back({all[i].t, change, normal * double(step * change)});
    }
    i = j;
  }
}

}  // namespace softtrace

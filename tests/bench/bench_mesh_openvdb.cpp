// OpenVDB's volumeToMesh on the field bench_mesh.cpp meshes: the 1000-blob scene of
// tools/blob_scene.py over its bounds, N cells along the longest side, 2 threads. A well-kept
// library should replace our mesher where measurement says it beats it; this is that measurement
// (docs/performance.md "Meshing"), compiled into build/tests/softtrace_mesh_bench beside
// BM_MeshBlobs1000 where Debian's libopenvdb-dev is installed.
//
// OpenVDB meshes a sampled grid, so it is given the samples as cheaply as we can make them, with
// our own pruning: the lattice is cut into OpenVDB's leaves of 8^3 points; a leaf whose box (one
// point wider on each side, so that every edge leaving a sampled leaf ends at a sampled point or at
// a point of known sign) cannot hold the surface by the box evaluator's interval is stored as a
// constant tile (inside) or left to the background (outside); the other leaves are sampled by the
// batched evaluator on the program pruned to the leaf. volumeToMesh then places vertices by linear
// interpolation between samples (no edge solve, no exact normals, no guarantee against
// self-intersections: docs/mesh.md), so it does less than mesh() for each vertex.
#include <benchmark/benchmark.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "bench_mesh_scene.h"
#include "eval/eval.h"
#include "mesh/mesh.h"
#include "mesh_check.h"
#include "model/program_builder.h"

namespace softtrace {
namespace {

constexpr int kLeaf = 8;  // openvdb::FloatTree's leaf: 8^3 voxels

// One sampled leaf: its origin (in lattice points) and its values, x slowest as OpenVDB stores
// them.
struct LeafSamples {
  openvdb::Coord origin;
  std::array<float, kLeaf * kLeaf * kLeaf> v;
};

// What the leaves of a lattice hold: sampled leaves, and the origins of leaves wholly inside.
struct Sampled {
  std::vector<LeafSamples> leaves;
  std::vector<openvdb::Coord> inside;
};

// The field over the lattice of points lo + h * (i, j, k), 0 <= i <= n[axis], as OpenVDB's level
// set convention wants it: negative inside (inside_sign * (f - iso) > 0).
Sampled sample(const Program& p, double iso, double inside_sign, const Vec3& lo, double h,
               const int n[3]) {
  int leaves[3];
  for (int a = 0; a < 3; ++a) leaves[a] = n[a] / kLeaf + 1;
  const int count = leaves[0] * leaves[1] * leaves[2];
  // Each leaf's verdict: 0 outside (background), 1 inside (a tile), 2 sampled (index into slots).
  std::vector<int> kind(count, 0);
  std::vector<LeafSamples> slots(count);
  // Leaf `id`'s first lattice point (leaves numbered x slowest).
  const auto origin = [&](int id) {
    return openvdb::Coord(id / (leaves[1] * leaves[2]) * kLeaf,
                          (id / leaves[2]) % leaves[1] * kLeaf, id % leaves[2] * kLeaf);
  };
  tbb::parallel_for(0, count, [&](int id) {
    thread_local Workspace ws;
    const openvdb::Coord c = origin(id);
    const int o[3] = {c.x(), c.y(), c.z()};
    const Box box{
        {lo.x + h * (o[0] - 1), lo.y + h * (o[1] - 1), lo.z + h * (o[2] - 1)},
        {lo.x + h * (o[0] + kLeaf), lo.y + h * (o[1] + kLeaf), lo.z + h * (o[2] + kLeaf)}};
    ws.fit(p);
    const BoxBounds b = bounds(p, box, ws);
    if (b.value.lo > iso || b.value.hi < iso) {
      const bool in = (b.value.lo > iso) == (inside_sign > 0);
      kind[id] = in ? 1 : 0;
      return;
    }
    kind[id] = 2;
    LeafSamples& s = slots[id];
    s.origin = c;
    const Code code(ws.view);
    double x[kBatch], y[kBatch], z[kBatch], f[kBatch];
    int lanes = 0, first = 0;
    for (int idx = 0; idx < kLeaf * kLeaf * kLeaf; ++idx) {
      const int i = idx / (kLeaf * kLeaf), j = (idx / kLeaf) % kLeaf, k = idx % kLeaf;
      x[lanes] = lo.x + h * (o[0] + i);
      y[lanes] = lo.y + h * (o[1] + j);
      z[lanes] = lo.z + h * (o[2] + k);
      if (++lanes == kBatch || idx + 1 == kLeaf * kLeaf * kLeaf) {
        values(code, x, y, z, lanes, f, ws);
        for (int l = 0; l < lanes; ++l) s.v[first + l] = float(-inside_sign * (f[l] - iso));
        first += lanes;
        lanes = 0;
      }
    }
  });
  Sampled out;
  for (int id = 0; id < count; ++id) {
    if (kind[id] == 2) out.leaves.push_back(slots[id]);
    if (kind[id] == 1) out.inside.push_back(origin(id));
  }
  return out;
}

void BM_OpenVdbBlobs1000(benchmark::State& state) {
  openvdb::initialize();
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  const SceneObject& o = mesh_bench_blobs().objects.front();
  const Program p = compile(*o.field);
  const int cells = int(state.range(0));
  const Vec3 size = o.bounds.hi - o.bounds.lo;
  const double h = std::max({size.x, size.y, size.z}) / cells;
  const int n[3] = {int(std::ceil(size.x / h)), int(std::ceil(size.y / h)),
                    int(std::ceil(size.z / h))};
  size_t points = 0, faces = 0, sampled = 0;
  double sampling = 0;  // seconds spent in sample(), summed over the iterations
  std::vector<openvdb::Vec3s> pts;
  std::vector<openvdb::Vec3I> tris;
  std::vector<openvdb::Vec4I> quads;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const Sampled s = sample(p, o.iso, o.inside_sign, o.bounds.lo, h, n);
    sampling += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Outside leaves hold the background (+1: outside, in field units), inside ones a tile of -1.
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(1.0f);
    openvdb::FloatTree& tree = grid->tree();
    for (const openvdb::Coord& c : s.inside) tree.addTile(1, c, -1.0f, false);
    for (const LeafSamples& l : s.leaves) {
      auto* leaf = new openvdb::FloatTree::LeafNodeType(l.origin, 1.0f, true);
      for (int idx = 0; idx < kLeaf * kLeaf * kLeaf; ++idx) leaf->setValueOnly(idx, l.v[idx]);
      tree.addLeaf(leaf);
    }
    pts.clear();
    tris.clear();
    quads.clear();
    openvdb::tools::volumeToMesh(*grid, pts, tris, quads, 0.0, 0.0);
    points = pts.size();
    faces = tris.size() + 2 * quads.size();
    sampled = s.leaves.size();
    benchmark::DoNotOptimize(pts.data());
  }
  // What the mesh promises, untimed: mesh_check's counts (its quads split into two triangles),
  // and how far the vertices lie from the surface, |f - iso| / |grad f| in cells (mesh() keeps
  // it below 1e-3).
  Mesh m;
  for (const openvdb::Vec3s& v : pts)
    m.vertices.push_back(o.bounds.lo + h * Vec3{double(v.x()), double(v.y()), double(v.z())});
  for (const openvdb::Vec3I& t : tris) m.faces.push_back({t[0], t[1], t[2]});
  for (const openvdb::Vec4I& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  const mesh_check::Report r = mesh_check::check(m);
  Workspace ws;
  ws.fit(p);
  double worst = 0;
  for (const Vec3& v : m.vertices) {
    Vec3 g;
    const double f = gradient_pruned(p, v, &g, ws);
    worst = std::max(worst, std::abs(f - o.iso) / std::max(length(g), 1e-300) / h);
  }
  state.counters["boundary_edges"] = double(r.boundary_edges);
  state.counters["nonmanifold_edges"] = double(r.nonmanifold_edges);
  state.counters["worst_off_surface_cells"] = worst;
  state.counters["vertices"] = double(points);
  state.counters["faces"] = double(faces);
  state.counters["sampled_leaves"] = double(sampled);
  state.counters["sample_ms"] = 1e3 * sampling / double(state.iterations());
}
BENCHMARK(BM_OpenVdbBlobs1000)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace softtrace

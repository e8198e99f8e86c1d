// Triangle meshes of one object's field: the surface {f = iso} over a region, cut from a lattice
// of cubic cells by marching tetrahedra (each cube split into the six tetrahedra of Kuhn's
// triangulation), with every vertex on a lattice edge where the exact field crosses iso.
//
// What a mesh from `mesh()` is, by construction (docs/mesh.md gives the reasons):
// - closed: where the region cuts the solid, a flat cap on the region's face closes it;
// - manifold: every edge lies in exactly two faces (each lattice edge holds one shared vertex);
// - oriented outward, with normals from the exact gradient (the cap's: the face's outward axis);
// - free of self-intersections: each triangle lies in its tetrahedron and meets the triangles of
//   the next one only in their shared vertices and edges;
// - without degenerate faces: a vertex sits at least kEdgeMargin of its edge from either end;
// - vertices on the surface: the crossing is solved on the edge (bracketed Illinois) to within
//   kEdgeTolerance of the edge's length, so |f - iso| / |grad f| stays far below 1e-3 cells.
// The same bits for any thread count. Memory grows with the surface: the lattice is visited in
// blocks, and the box evaluator's intervals skip the blocks that cannot hold the surface.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "math/box.h"
#include "mesh/mesh_array.h"
#include "program/program.h"

namespace softtrace {

// The solid to mesh: {inside_sign * (f - iso) >= 0}, f the program's value (docs/math.md §1:
// +1 for soft objects, whose inside is f >= iso; -1 for the zero and constructive conventions).
struct MeshField {
  const Program* program = nullptr;
  double iso = 0.5;
  double inside_sign = 1;
};

struct MeshOptions {
  // The cells' edge length; 0: the region's longest side over `cells`.
  double voxel = 0;
  int cells = 128;
  int threads = 1;
  // The colour given to every vertex.
  Vec3 color{0.8, 0.8, 0.8};
  // Called from the worker threads (at most once per block) with the fraction done, 0..1.
  std::function<void(double)> progress;
  // Polled between blocks: once true, mesh() throws MeshCancelled.
  const std::atomic<bool>* cancel = nullptr;
};

// The arrays are std::vectors whose resize(n) leaves the new elements unwritten (mesh_array.h).
struct Mesh {
  MeshArray<Vec3> vertices;
  MeshArray<std::array<uint32_t, 3>> faces;  // counter-clockwise seen from outside
  MeshArray<Vec3> normals;                   // unit, outward, one per vertex
  MeshArray<Vec3> colors;                    // linear RGB, one per vertex
  Box lattice;  // the region rounded out to whole cells (the cap lies on its faces)
  double voxel = 0;
};

struct MeshCancelled : std::runtime_error {
  MeshCancelled() : std::runtime_error("meshing cancelled") {}
};

// The lattice has at most this many cells along an axis (edge keys must fit 64 bits, and a
// finer lattice would not fit in memory on its surface alone).
constexpr int kMaxCells = 65536;

// Meshes `field` over `region` (a bounded box). Throws std::invalid_argument for a region that is
// not bounded, a voxel that is not positive and finite, or a lattice beyond kMaxCells per axis.
Mesh mesh(const MeshField& field, const Box& region, const MeshOptions& options);

// The volume the mesh encloses (the divergence theorem over its faces).
double enclosed_volume(const Mesh& m);

}  // namespace softtrace

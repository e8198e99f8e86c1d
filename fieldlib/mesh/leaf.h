// One leaf block of the mesher: the cells [c0, c1) of the lattice, meshed on their own. Corner
// values come from the batched values evaluator on the program pruned to the block; each edge
// crossing is solved on the exact field. A vertex on the block's faces is found again by the
// neighbours that share its edge, with the same corner values (the pruned program's value at a
// point does not depend on the box it was pruned to: only children that are exactly 0 there are
// dropped); one of them solves it (EdgePlace), and the mesher welds them by their edge key.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/illinois.h"
#include "mesh/lattice.h"
#include "mesh/mesh.h"
#include "mesh/sampler.h"

namespace softtrace {

// A vertex sits at least this fraction of its edge's length from either end, so that no face
// is degenerate (a vertex at a lattice point would collapse the faces around it). It moves a
// vertex off the surface by at most this fraction of an edge (sqrt 3 cells at most).
constexpr double kEdgeMargin = 1e-4;
// The crossing is solved to this fraction of the edge (solve_edges in leaf.cpp).
constexpr double kEdgeTolerance = 1e-4;

// Where a leaf's vertex lies. An edge on the block's boundary is held by every leaf around it,
// and solved by one only: the leaf for which it lies on no lower face (the leaves below hold the
// edge's cells too, so they are leaves as well: their interval cannot exclude a crossing).
enum class EdgePlace : uint8_t {
  Interior,  // this leaf's alone
  Solved,    // on the boundary, solved here
  Borrowed,  // on a lower face: its position is the solving leaf's (mesh.cpp's weld)
};

// What the normal needs of a vertex's lattice edge, in a byte: the edge's axes (bits 0-2, its key's
// direction), whether it runs down them from its inside end to its outside end (kEdgeDown) and
// whether an end is a padding point (kEdgeCapped).
constexpr uint8_t kEdgeDown = 8, kEdgeCapped = 16;
// The direction from the edge's inside end to its outside end (not of unit length).
inline Vec3 edge_outward(uint8_t code) {
  const double s = code & kEdgeDown ? -1 : 1;
  return {code & 1 ? s : 0.0, code & 2 ? s : 0.0, code & 4 ? s : 0.0};
}

// The polygon a tetrahedron cuts: a triangle, or a quadrilateral (v[3] too) that the mesher splits
// along its shorter diagonal once every position is known (after the weld).
// A leaf's vertices are numbered in 16 bits (a cut in 10 bytes: the leaves' cuts are the largest
// part of what the mesher holds before the weld): a leaf has at most kMaxLeafPoints points, each
// the lower end of at most 7 edges.
constexpr int kMaxLeafPoints = 65536 / 8;
struct LeafCut {
  uint16_t v[4];  // indices into the leaf's vertices, counter-clockwise seen from outside
  bool quad;
};

struct LeafMesh {
  std::vector<uint64_t> keys;  // each vertex's lattice edge
  std::vector<EdgePlace> place;
  std::vector<Vec3> positions;  // not a number where Borrowed
  std::vector<uint8_t> edge;    // each vertex's EdgeCode (its normal's, taken after the weld)
  std::vector<LeafCut> cuts;
};

// The unit outward normal at vertex p: -inside_sign grad f / |grad f| from the exact gradient,
// the cap's face axis where the cap (the vertex's edge reaches the padding) is what p lies on,
// and the edge's direction out at a critical point of the field. `edge` is the vertex's EdgeCode.
// Computed once per welded vertex, after the weld, with the sampler prepared for the leaf that
// solved it (mesh.cpp).
Vec3 vertex_normal(const MeshField& field, const FieldSampler& sampler, const Lattice& lattice,
                   const Vec3& p, uint8_t edge, SamplerScratch& scratch);

// Meshes leaves one after another, keeping its buffers from one to the next (one per thread).
class LeafMesher {
 public:
  LeafMesher(const MeshField& field, const FieldSampler& sampler, const Lattice& lattice)
      : field_(field), sampler_(sampler), lattice_(lattice) {}

  // Meshes cells c0..c1-1 (per axis), at most kMaxLeafPoints points, into *out (replaced).
  void run(const int c0[3], const int c1[3], SamplerScratch& scratch, LeafMesh* out);

 private:
  bool inside(double f) const { return field_.inside_sign > 0 ? f >= field_.iso : f <= field_.iso; }
  // The function whose zero the vertex is: g = inside_sign (f - iso), >= 0 inside, and on an
  // edge from a padding point the solid cut by the lattice box, min(g, inside distance).
  double solved(double f, const Vec3& p, bool capped) const;
  void solve_edges(SamplerScratch& scratch, LeafMesh* out);

  const MeshField& field_;
  const FieldSampler& sampler_;
  const Lattice& lattice_;
  int m_[3] = {0, 0, 0};         // points per axis in the block
  std::vector<double> axis_[3];  // the block's points' coordinates along each axis
  std::vector<double> values_;
  std::vector<uint8_t> inside_;
  std::vector<int32_t> slot_;  // local point * 8 + direction -> vertex, or -1
  // The leaf's vertices' keys and places and its cuts, as they are found (copied to the LeafMesh
  // at their size once the leaf is done).
  std::vector<uint64_t> keys_;
  std::vector<EdgePlace> place_;
  std::vector<LeafCut> cuts_;
  struct Edge {
    Vec3 a, b;  // inside end, outside end
    double ga, gb;
    bool capped;   // an end is a padding point
    uint8_t code;  // its EdgeCode
    bool solve;    // not Borrowed
    double tc,
        gc;  // a third point of the edge's line (at a + tc (b - a)) and its value; tc 0: none
  };
  std::vector<Edge> edges_;
  // solve_edges' state of each edge's search, and the queue of edges not done.
  struct EdgeState {
    IllinoisBracket bracket;
    double px, pg;          // the previous evaluation (an end, at first)
    double qx, qg;          // the one before (the inside end, at first)
    double rx = 0, rg = 0;  // and the one before that (none before the first step)
    double t = -1;          // the solution, once found
    uint8_t slow = 0;       // steps in a row that did not halve the bracket
    uint8_t steps = 0;      // steps taken
  };
  std::vector<EdgeState> state_;
  std::vector<uint32_t> active_;
};

}  // namespace softtrace

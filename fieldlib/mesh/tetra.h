// Marching tetrahedra on Kuhn's triangulation of the cube (Freudenthal 1942, Kuhn 1960): the
// cube's corners 0..7 (bit a set: the upper side along axis a) split into six tetrahedra, one per
// order of the axes, each the path 0 -> e_a -> e_a + e_b -> 7 along the main diagonal. Every cube
// of the lattice is split the same way, so the split of each square face agrees between the two
// cubes that share it, and the tetrahedra triangulate the whole lattice.
//
// In a tetrahedron whose corners are on both sides of the surface, the surface is cut as one
// triangle (one corner on its own side) or a quadrilateral (two and two) with a vertex on each
// edge that changes side. Both are listed here with each edge as (inside corner, outside corner)
// and wound counter-clockwise seen from outside (from the outside corners).
#pragma once

#include <cstdint>

namespace softtrace {

// The six tetrahedra as cube corners, each in positive orientation (det(c1-c0, c2-c0, c3-c0) > 0).
extern const uint8_t kKuhnTetrahedra[6][4];

struct TetCut {
  int count = 0;        // 0 (no surface), 3 (triangle) or 4 (quadrilateral, a cycle)
  uint8_t in[4] = {};   // edge e joins cube corner in[e] (inside)...
  uint8_t out[4] = {};  // ...to cube corner out[e] (outside)
};

// The cut of tetrahedron `tet` (0..5) when the corners whose bits are set in `inside` (bit i for
// the tetrahedron's corner i) are inside.
const TetCut& tet_cut(int tet, int inside);

}  // namespace softtrace

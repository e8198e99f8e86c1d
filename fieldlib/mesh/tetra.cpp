#include "mesh/tetra.h"

#include <array>
#include <utility>

namespace softtrace {

// The path 0 -> e_a -> e_a + e_b -> 7 for each order (a, b, c) of the axes. Its orientation is
// det(e_a, e_b, e_c), the order's sign; the odd orders have their last two corners swapped.
const uint8_t kKuhnTetrahedra[6][4] = {
    {0, 1, 3, 7},  // x y z (even)
    {0, 1, 7, 5},  // x z y (odd, swapped)
    {0, 2, 7, 3},  // y x z (odd, swapped)
    {0, 2, 6, 7},  // y z x (even)
    {0, 4, 5, 7},  // z x y (even)
    {0, 4, 7, 6},  // z y x (odd, swapped)
};

namespace {

bool odd(const int p[4]) {
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
  return inversions & 1;
}

// For a positively oriented tetrahedron (v0, v1, v2, v3), the face (v1, v2, v3) is wound
// counter-clockwise seen from outside, away from v0; so is the section of the edges from v0 taken
// in that order. With the corners ordered as an even permutation (i, j, k, l), the triangle on
// edges (i,j), (i,k), (i,l) faces away from i, and the quadrilateral (i1,o1), (i1,o2), (i2,o2),
// (i2,o1) of an even (i1, i2, o1, o2) faces the outside pair.
TetCut make_cut(const uint8_t* corner, int inside) {
  TetCut cut;
  int ins[4], outs[4], ni = 0, no = 0;
  for (int v = 0; v < 4; ++v) (inside >> v & 1 ? ins[ni++] : outs[no++]) = v;
  if (ni == 1 || ni == 3) {
    // The corner alone on its side, then the other three, made an even permutation.
    const int alone = ni == 1 ? ins[0] : outs[0];
    int p[4] = {alone, 0, 0, 0};
    for (int v = 0, k = 1; v < 4; ++v)
      if (v != alone) p[k++] = v;
    if (odd(p)) std::swap(p[2], p[3]);
    // Facing away from an inside corner; towards an outside one (the reverse order).
    if (ni == 3) std::swap(p[2], p[3]);
    cut.count = 3;
    for (int e = 0; e < 3; ++e) {
      cut.in[e] = corner[ni == 1 ? p[0] : p[e + 1]];
      cut.out[e] = corner[ni == 1 ? p[e + 1] : p[0]];
    }
  } else if (ni == 2) {
    int p[4] = {ins[0], ins[1], outs[0], outs[1]};
    if (odd(p)) std::swap(p[2], p[3]);
    const int cycle[4][2] = {{p[0], p[2]}, {p[0], p[3]}, {p[1], p[3]}, {p[1], p[2]}};
    cut.count = 4;
    for (int e = 0; e < 4; ++e) {
      cut.in[e] = corner[cycle[e][0]];
      cut.out[e] = corner[cycle[e][1]];
    }
  }
  return cut;
}

struct Table {
  TetCut cut[6][16];
  Table() {
    for (int t = 0; t < 6; ++t)
      for (int m = 0; m < 16; ++m) cut[t][m] = make_cut(kKuhnTetrahedra[t], m);
  }
};

}  // namespace

const TetCut& tet_cut(int tet, int inside) {
  static const Table table;
  return table.cut[tet][inside];
}

}  // namespace softtrace

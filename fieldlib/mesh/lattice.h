// The mesher's lattice: cubic cells of edge h over the region rounded out to whole cells
// (`box`), sampled at the cells' centres, with one more layer of points half a cell outside
// `box` on every side. Those padding points count as outside the solid, so the surface is closed
// by a cap on `box`'s faces wherever the region cuts the solid: there the mesher solves for
// min(g, inside_distance), the solid intersected with the box.
//
// Points are numbered 0..n+1 along each axis (0 and n+1 the padding), cells 0..n (cell c between
// points c and c+1). A lattice edge is named by its lower point and its direction: a non-empty
// set of axes (bit a for axis a), since every edge of Kuhn's tetrahedra joins a cube corner to
// one with more bits set.
#pragma once

#include <algorithm>
#include <cstdint>

#include "math/box.h"

namespace softtrace {

struct Lattice {
  Box box;  // the cells' union; its faces hold the caps
  double h = 0;
  int n[3] = {0, 0, 0};  // cells per axis inside `box`

  int points(int axis) const { return n[axis] + 2; }
  bool padding(int i, int j, int k) const {
    return i == 0 || j == 0 || k == 0 || i == n[0] + 1 || j == n[1] + 1 || k == n[2] + 1;
  }
  double coordinate(int axis, int i) const { return box.lo[axis] + (i - 0.5) * h; }
  Vec3 point(int i, int j, int k) const {
    return {coordinate(0, i), coordinate(1, j), coordinate(2, k)};
  }
  // The box spanned by points lo..hi (inclusive) of each axis.
  Box span(const int lo[3], const int hi[3]) const {
    return {point(lo[0], lo[1], lo[2]), point(hi[0], hi[1], hi[2])};
  }
  // Edge (i, j, k) + direction d (1..7): unique over the lattice, and in lattice order.
  uint64_t edge_key(int i, int j, int k, int d) const {
    return ((uint64_t(k) * uint64_t(points(1)) + uint64_t(j)) * uint64_t(points(0)) + uint64_t(i)) *
               8 +
           uint64_t(d);
  }
  // How far p lies inside `box` (negative outside): the distance to the nearest face inside, and
  // a lower bound of the distance outside. Its zero set is the cap.
  double inside_distance(const Vec3& p) const {
    double d = p.x - box.lo.x;
    for (int a = 0; a < 3; ++a) d = std::min({d, p[a] - box.lo[a], box.hi[a] - p[a]});
    return d;
  }
  // The outward normal of the face of `box` nearest p (the cap's normal at p).
  Vec3 cap_normal(const Vec3& p) const {
    int best = 0;
    double d = p.x - box.lo.x, sign = -1;
    for (int a = 0; a < 3; ++a) {
      if (p[a] - box.lo[a] < d) best = a, d = p[a] - box.lo[a], sign = -1;
      if (box.hi[a] - p[a] < d) best = a, d = box.hi[a] - p[a], sign = 1;
    }
    Vec3 nrm;
    nrm[best] = sign;
    return nrm;
  }
};

}  // namespace softtrace

// Parallel planes |X·n|/a and the one-branch plane [X·n]_+/a (docs/math.md §2.3, §2.4) as kernels
// shared by the model nodes (distances_planes.cpp) and the program's ParallelPlanes and
// OneBranchPlane instructions, so both compute the same bits. The normal n is a unit vector, so a
// is the distance to a plane and 1/a bounds the slope everywhere. The bounds take the range of X·n
// over the box (dot_range), which the segment pass also reads for the sign of X·n.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/box.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

struct PlaneParams {
  Vec3 n;  // unit normal
  double a;
};

// The exact image of X·n over a box (interval arithmetic, outward rounded).
inline Interval dot_range(const Box& b, const Vec3& n) {
  return scaled(n.x, b.axis(0)) + scaled(n.y, b.axis(1)) + scaled(n.z, b.axis(2));
}

// |X·n|/a   — 000 Eq. 2 (planes), 002 f_p, docs/math.md §2.3.
inline double parallel_planes(const PlaneParams& m, const Vec3& p, Vec3* grad) {
  const double s = dot(p, m.n);
  if (grad) *grad = m.n * ((s > 0 ? 1.0 : (s < 0 ? -1.0 : 0.0)) / m.a);
  return std::abs(s) / m.a;
}

// Value interval and Lipschitz bound of |X·n|/a where X·n lies in `s`: the slope is 1/a anywhere.
inline void parallel_planes_bounds(const PlaneParams& m, Interval s, Interval* value,
                                   double* lipschitz) {
  *value = divided(abs(s), m.a);
  *lipschitz = 1 / m.a;
}

// [X·n]_+/a   — 002 §4.5 f_o (R4), docs/math.md §2.4.
inline double one_branch_plane(const PlaneParams& m, const Vec3& p, Vec3* grad) {
  const double s = dot(p, m.n);
  if (grad) *grad = s > 0 ? m.n / m.a : Vec3{};
  return std::max(s, 0.0) / m.a;
}

// Value interval and Lipschitz bound of [X·n]_+/a where X·n lies in `s`: slope 1/a, and 0 where
// X·n <= 0 throughout (f is 0 there).
inline void one_branch_plane_bounds(const PlaneParams& m, Interval s, Interval* value,
                                    double* lipschitz) {
  *value = divided(max(s, Interval(0)), m.a);
  *lipschitz = s.hi > 0 ? 1 / m.a : 0.0;
}

}  // namespace softtrace

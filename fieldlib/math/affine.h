// 3x3 linear maps for affine placement (docs/math.md §2.15): products, the inverse by the adjugate,
// and a derived upper bound on the operator (spectral) norm, which is what a placement multiplies
// Lipschitz bounds by. Row-major, as Mat3.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

inline Mat3 times(const Mat3& a, const Mat3& b) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m.r[i][j] = a.r[i].x * b.r[0][j] + a.r[i].y * b.r[1][j] + a.r[i].z * b.r[2][j];
  return m;
}

inline Mat3 transposed(const Mat3& a) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.r[i][j] = a.r[j][i];
  return m;
}

inline double determinant(const Mat3& a) {
  return dot(a.r[0], cross(a.r[1], a.r[2]));
}

// a^-1 = adj(a)/det(a): the adjugate's columns are the cross products of a's rows. Non-finite
// entries where det is 0 (callers refuse such matrices first).
inline Mat3 inverse(const Mat3& a) {
  const Vec3 c0 = cross(a.r[1], a.r[2]), c1 = cross(a.r[2], a.r[0]), c2 = cross(a.r[0], a.r[1]);
  const double inv = 1 / dot(a.r[0], c0);
  Mat3 m;
  for (int i = 0; i < 3; ++i) m.r[i] = Vec3{c0[i], c1[i], c2[i]} * inv;
  return m;
}

// An upper bound on |a|_2 = sqrt(λ_max(a^T a)), derived, not sampled. For the symmetric B = a^T a
// with q = tr B / 3 and p = sqrt(tr((B - qI)^2) / 6), the eigenvalues are q + 2p cos(φ + 2πk/3)
// with cos 3φ = det((B - qI)/p) / 2 (the trigonometric solution of the characteristic cubic), so
// λ_max = q + 2p cos φ, and q + 2p and tr B bound it whatever the rounding of φ. The computed
// λ_max errs by a few ulps of q + 2p (cos(acos(r)/3) is smooth in r up to r = 1); 1e-12 of it
// covers that with room, and the least of the three bounds is kept.
inline double operator_norm_bound(const Mat3& a) {
  const Mat3 B = times(transposed(a), a);
  const double tr = B.r[0].x + B.r[1].y + B.r[2].z;
  const double off = B.r[0].y * B.r[0].y + B.r[0].z * B.r[0].z + B.r[1].z * B.r[1].z;
  const double q = tr / 3;
  const double p2 = (B.r[0].x - q) * (B.r[0].x - q) + (B.r[1].y - q) * (B.r[1].y - q) +
                    (B.r[2].z - q) * (B.r[2].z - q) + 2 * off;
  const double p = std::sqrt(p2 / 6);
  double lambda = q;
  if (p > 0) {
    Mat3 C = B;
    for (int i = 0; i < 3; ++i) {
      C.r[i][i] -= q;
      C.r[i] = C.r[i] * (1 / p);
    }
    const double r = std::clamp(determinant(C) / 2, -1.0, 1.0);
    lambda = q + 2 * p * std::cos(std::acos(r) / 3);
  }
  const double cap = q + 2 * p;
  const double top = std::min({tr, cap, lambda + 1e-12 * cap}) * (1 + 1e-12);
  return iv::up(std::sqrt(top));
}

}  // namespace softtrace

#include "mesh/blob_bounds.h"

#include <algorithm>
#include <cmath>

#include "kernels/potentials.h"

namespace softtrace {

namespace {
// P(r) = r^2 (c2 + c3 r) over r in [rlo, rhi], P = 0 where r <= 0 (outside the support):
// its values at the ends and at its turning point r = -2 c2 / (3 c3) where that lies between.
Interval potential_range(double c2, double c3, double rlo, double rhi) {
  auto P = [&](double r) { return polynomial_potential(r, c2, c3); };
  rlo = std::max(rlo, 0.0);
  rhi = std::max(rhi, 0.0);
  const double a = P(rlo), b = P(rhi);
  Interval v{std::min(a, b), std::max(a, b)};
  if (c3 != 0) {
    const double turn = -2 * c2 / (3 * c3);
    if (turn > rlo && turn < rhi) {
      v.lo = std::min(v.lo, P(turn));
      v.hi = std::max(v.hi, P(turn));
    }
  }
  return v;
}
}  // namespace

bool blob_intervals_apply(const BlobSum& sum) {
  for (const BlobSum::Frame& f : sum.frames())
    if (f.inv_axis2 > 0) return false;
  return true;
}

Interval blob_interval(const BlobSum& sum, const int32_t* ids, int n, const Box& box,
                       std::vector<int32_t>* kept) {
  const Vec3 mid = box.center(), half = box.extent() * 0.5;
  Interval v{0, 0};
  for (int i = 0; i < n; ++i) {
    const BlobSum::Blob& b = sum.blobs()[size_t(ids[i])];
    // The range of |q|^2 over the box.
    double near2 = 0, far2 = 0;
    if (b.inv_r2 > 0) {
      for (int a = 0; a < 3; ++a) {
        const double gap = std::max({box.lo[a] - b.centre[a], b.centre[a] - box.hi[a], 0.0});
        const double far =
            std::max(std::abs(box.lo[a] - b.centre[a]), std::abs(box.hi[a] - b.centre[a]));
        near2 += gap * gap;
        far2 += far * far;
      }
      near2 *= b.inv_r2;
      far2 *= b.inv_r2;
    } else {
      // q_a = L_a . x + k_a lies within L_a . mid + k_a +- |L_a| . half (|L_a| elementwise),
      // widened by 1e-14 of its terms' sizes for the rounding of the centre's value.
      const BlobSum::Frame& f = sum.frames()[size_t(ids[i])];
      for (int a = 0; a < 3; ++a) {
        const Vec3& row = f.L.r[a];
        const double at = dot(row, mid) + f.k[a];
        const double size = std::abs(row.x * mid.x) + std::abs(row.y * mid.y) +
                            std::abs(row.z * mid.z) + std::abs(f.k[a]);
        const double spread = std::abs(row.x) * half.x + std::abs(row.y) * half.y +
                              std::abs(row.z) * half.z + 1e-14 * size;
        const double gap = std::max(std::abs(at) - spread, 0.0), far = std::abs(at) + spread;
        near2 += gap * gap;
        far2 += far * far;
      }
    }
    // r = 1 - |q|^2 <= 0 all over the box (by a relative 1e-9, for rounding): the blob adds 0.
    if (near2 > 1 + 1e-9) continue;
    kept->push_back(ids[i]);
    const Interval p = potential_range(b.c2, b.c3, 1 - far2 * (1 + 1e-12), 1 - near2 * (1 - 1e-12));
    v.lo += p.lo;
    v.hi += p.hi;
  }
  return v;
}

}  // namespace softtrace

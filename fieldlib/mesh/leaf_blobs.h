// The blobs of a sum of polynomial blobs (eval/blob_ray.h's BlobSum) that can be non-zero in one
// leaf of the mesher, summed in closed form at many points at once. A leaf's pruned program keeps
// every blob whose support box meets the leaf (about 35 on the 1000-blob scene, where a point lies
// in about 14) and walks instructions lane by lane; here one query of the sum's support tree per
// leaf finds those blobs, a ball whose sphere misses the leaf's box is dropped (a ball's support
// box holds twice the ball's volume), and each point takes each kept blob's potential
// P(r) = c2 r^2 + c3 r^3, r = 1 - |q|^2 (docs/math.md §3.3-§3.4), in a loop over the points that
// the compiler vectorises.
//
// The same bits at a point from every leaf that holds it: the kept blobs are summed in increasing
// child order, and a blob that does not hold the point adds exactly 0, so the sum is that of the
// blobs holding the point, in their order, whichever superset a leaf kept.
#pragma once

#include <cstdint>
#include <vector>

#include "eval/blob_ray.h"
#include "math/box.h"

namespace softtrace {

class LeafBlobs {
 public:
  // Keeps the blobs of `sum` (the field of `p`) that may be non-zero inside `box`.
  void select(const BlobSum& sum, const Program& p, const Box& box);
  // f at (x[i], y[i], z[i]), i < n, points inside the box of the last select().
  void values(const double* x, const double* y, const double* z, int n, double* f) const;
  // f at the points (xs[i], ys[j], zs[k]) of a grid inside the box, into f[i + m0 (j + m1 k)]. A
  // ball skips the planes and rows of the grid that its sphere misses (r <= 0 there, as values()
  // computes it: the same bits as values() at every point).
  void grid(const double* xs, const double* ys, const double* zs, const int m[3], double* f);
  // f(x) and ∇f(x) at a point inside the box: BlobSum::gradient's sum over the same blobs in the
  // same order, so the same bits.
  double gradient(const Vec3& x, Vec3* grad) const;
  int size() const { return static_cast<int>(ids_.size()); }

 private:
  // Adds blob `id`'s potential at the n points to f[].
  void add(int32_t id, const double* x, const double* y, const double* z, int n, double* f) const;

  const BlobSum* sum_ = nullptr;
  std::vector<int32_t> ids_;           // ascending
  std::vector<double> row_y_, row_z_;  // grid(): a row's y and z, for blobs that are not balls
};

}  // namespace softtrace

// The field as the mesher samples it: values at batches of points (the leaves' corners, the edge
// solver's steps) and the exact gradient at a vertex, all inside the box of one leaf. Where the
// program is a sum of polynomial blobs (eval/blob_ray.h's BlobSum: Murakami's, Wyvill's or the
// cubic potential of an ellipsoid or a capsule), the leaf's blobs are summed in closed form
// (leaf_blobs.h); that is several times cheaper than walking the program pruned to the leaf and
// than the forward-mode gradient walk. Any other program is walked by the evaluators of eval.h.
//
// A point's value depends on the point alone, whichever leaf asks and on whichever thread (the
// blobs are summed in increasing child order, leaf_blobs.h; the pruned program's sum keeps the
// program's order and drops exact zeros only), so neighbouring leaves classify a shared corner
// alike.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "math/box.h"
#include "mesh/leaf_blobs.h"

namespace softtrace {

// The most points one values() call takes: kBatch for the evaluators; the closed-form sum takes
// more, so that each blob's constants are loaded once for all of a leaf's corners (5^3 = 125).
constexpr int kSamplerBatch = 128;

// One thread's scratch for a FieldSampler: the evaluators' workspace and the leaf's blobs.
struct SamplerScratch {
  Workspace ws;
  LeafBlobs blobs;
};

class FieldSampler {
 public:
  explicit FieldSampler(const Program& p) : program_(p), blobs_(BlobSum::of(p)) {}

  // Readies `s` for points inside `box` (the general path prunes the program to it).
  void prepare(const Box& box, SamplerScratch& s) const;
  // Readies `s` for gradient() only, at points inside `box` (the general path needs nothing).
  void prepare_gradients(const Box& box, SamplerScratch& s) const;
  // The program's blobs where it is a sum of polynomial blobs, else null.
  const BlobSum* blobs() const { return blobs_ ? &*blobs_ : nullptr; }
  // How many points values() takes at a time: kSamplerBatch for a sum of blobs, else kBatch.
  int batch() const { return blobs_ ? kSamplerBatch : kBatch; }
  // f at (x[i], y[i], z[i]), i < n <= batch(), all inside the box of the last prepare().
  void values(const double* x, const double* y, const double* z, int n, double* f,
              SamplerScratch& s) const;
  // f at the grid of points (xs[i], ys[j], zs[k]), i < m[0], j < m[1], k < m[2], inside the box
  // of the last prepare(), into f[i + m[0] (j + m[1] k)].
  void grid(const double* xs, const double* ys, const double* zs, const int m[3], double* f,
            SamplerScratch& s) const;
  // f(p) and ∇f(p) at p inside the box of the last prepare(): the exact gradient (the whole
  // program's, pruned to the point, for any field but a sum of blobs).
  double gradient(const Vec3& p, Vec3* grad, SamplerScratch& s) const;

 private:
  const Program& program_;
  std::optional<BlobSum> blobs_;
};

}  // namespace softtrace

// The field as the mesher samples it: values at batches of points (the leaves' corners, the edge
// solver's steps) and the exact gradient at a vertex. Where the program is a sum of polynomial
// blobs (eval/blob_ray.h's BlobSum: Murakami's, Wyvill's or the cubic potential of an ellipsoid
// or a capsule), each point sums the few blobs whose supports hold it, found by one query of the
// sum's support tree, in closed form; that is several times cheaper than walking the program
// pruned to a leaf (which keeps every blob whose support meets the leaf's box) and than the
// forward-mode gradient walk. Any other program is walked by the evaluators of eval.h.
//
// A point's value depends on the point alone, whichever leaf asks and on whichever thread (the
// blobs are summed in the tree's order for that point; the pruned program's sum keeps the
// program's order and drops exact zeros only), so neighbouring leaves classify a shared corner
// alike.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "eval/blob_ray.h"
#include "eval/eval.h"
#include "math/box.h"

namespace softtrace {

// One thread's scratch for a FieldSampler: the evaluators' workspace and the blob query's ids.
struct SamplerScratch {
  Workspace ws;
  std::vector<int32_t> ids;
};

class FieldSampler {
 public:
  explicit FieldSampler(const Program& p) : program_(p), blobs_(BlobSum::of(p)) {}

  // Readies `s` for points inside `box` (the general path prunes the program to it).
  void prepare(const Box& box, SamplerScratch& s) const;
  // f at (x[i], y[i], z[i]), i < n <= kBatch, all inside the box of the last prepare().
  void values(const double* x, const double* y, const double* z, int n, double* f,
              SamplerScratch& s) const;
  // f(p) and ∇f(p) anywhere (the whole program, pruned to the point).
  double gradient(const Vec3& p, Vec3* grad, SamplerScratch& s) const;

 private:
  const Program& program_;
  std::optional<BlobSum> blobs_;
};

}  // namespace softtrace

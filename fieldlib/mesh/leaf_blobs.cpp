#include "mesh/leaf_blobs.h"

#include <algorithm>

namespace softtrace {

void LeafBlobs::select(const BlobSum& sum, const Program& p, const Box& box) {
  sum_ = &sum;
  ids_.resize(size_t(sum.size()));  // the query's room for every child
  const int found = p.groups[size_t(sum.group())].bvh.query(box, ids_.data(), 0);
  // A ball is dropped where its sphere misses the box by a relative 1e-9 of its radius: every
  // point of the box (or an ulp of the radius outside it, as an edge's points may be) then has
  // r < 0, so the blob adds exactly 0 there in any leaf.
  int kept = 0;
  for (int i = 0; i < found; ++i) {
    const BlobSum::Blob& b = sum.blobs()[size_t(ids_[i])];
    if (b.inv_r2 > 0) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double gap = std::max({box.lo[a] - b.centre[a], b.centre[a] - box.hi[a], 0.0});
        d2 += gap * gap;
      }
      if (d2 * b.inv_r2 > 1 + 1e-9) continue;
    }
    ids_[size_t(kept++)] = ids_[size_t(i)];
  }
  ids_.resize(size_t(kept));
}

void LeafBlobs::values(const double* x, const double* y, const double* z, int n, double* f) const {
  std::fill(f, f + n, 0.0);
  for (const int32_t id : ids_) {
    const BlobSum::Blob& b = sum_->blobs()[size_t(id)];
    const double c2 = b.c2, c3 = b.c3;
    if (b.inv_r2 > 0) {
      // A ball: |q|^2 = |x - centre|^2 / radius^2.
      const double cx = b.centre.x, cy = b.centre.y, cz = b.centre.z, s = b.inv_r2;
      for (int l = 0; l < n; ++l) {
        const double dx = x[l] - cx, dy = y[l] - cy, dz = z[l] - cz;
        const double r = 1 - (dx * dx + dy * dy + dz * dz) * s;
        f[l] += r > 0 ? r * r * (c2 + c3 * r) : 0.0;
      }
      continue;
    }
    // Any other blob: q = L x + k, less its nearest point of a capsule's axis.
    const BlobSum::Frame& fr = sum_->frames()[size_t(id)];
    const Mat3& L = fr.L;
    for (int l = 0; l < n; ++l) {
      Vec3 w{L.r[0].x * x[l] + L.r[0].y * y[l] + L.r[0].z * z[l] + fr.k.x,
             L.r[1].x * x[l] + L.r[1].y * y[l] + L.r[1].z * z[l] + fr.k.y,
             L.r[2].x * x[l] + L.r[2].y * y[l] + L.r[2].z * z[l] + fr.k.z};
      if (fr.inv_axis2 > 0) w = w - fr.axis * std::clamp(dot(w, fr.axis) * fr.inv_axis2, 0.0, 1.0);
      const double r = 1 - dot(w, w);
      f[l] += r > 0 ? r * r * (c2 + c3 * r) : 0.0;
    }
  }
}

double LeafBlobs::gradient(const Vec3& x, Vec3* grad) const {
  double f = 0;
  Vec3 g;
  for (const int32_t id : ids_) {
    const BlobSum::Frame& frame = sum_->frames()[size_t(id)];
    const BlobSum::Blob& b = sum_->blobs()[size_t(id)];
    Vec3 w = frame.L * x + frame.k;
    if (frame.inv_axis2 > 0)
      w = w - frame.axis * std::clamp(dot(w, frame.axis) * frame.inv_axis2, 0.0, 1.0);
    const double r = 1 - dot(w, w);
    if (!(r > 0)) continue;
    f += r * r * (b.c2 + b.c3 * r);
    // dP/dr times ∇r = -2 L^T q.
    g += frame.L.transposed_times(w) * (-2 * r * (2 * b.c2 + 3 * b.c3 * r));
  }
  *grad = g;
  return f;
}

}  // namespace softtrace

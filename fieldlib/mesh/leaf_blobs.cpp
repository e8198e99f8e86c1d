#include "mesh/leaf_blobs.h"

#include <algorithm>

#include "kernels/potentials.h"

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
  for (const int32_t id : ids_) add(id, x, y, z, n, f);
}

void LeafBlobs::add(int32_t id, const double* x, const double* y, const double* z, int n,
                    double* f) const {
  const BlobSum::Blob& b = sum_->blobs()[size_t(id)];
  const double c2 = b.c2, c3 = b.c3;
  if (b.inv_r2 > 0) {
    // A ball: |q|^2 = |x - centre|^2 / radius^2.
    const double cx = b.centre.x, cy = b.centre.y, cz = b.centre.z, s = b.inv_r2;
    for (int l = 0; l < n; ++l) {
      const double dx = x[l] - cx, dy = y[l] - cy, dz = z[l] - cz;
      const double r = 1 - (dx * dx + dy * dy + dz * dz) * s;
      f[l] += r > 0 ? polynomial_potential(r, c2, c3) : 0.0;
    }
    return;
  }
  // Any other blob: its frame's q (BlobSum::Frame::q, as the ray path and gradient() take it).
  // A copy: f[] cannot alias it, so its numbers stay in registers across the loop.
  const BlobSum::Frame fr = sum_->frames()[size_t(id)];
  for (int l = 0; l < n; ++l) {
    const Vec3 w = fr.q({x[l], y[l], z[l]});
    const double r = 1 - dot(w, w);
    f[l] += r > 0 ? polynomial_potential(r, c2, c3) : 0.0;
  }
}

void LeafBlobs::grid(const double* xs, const double* ys, const double* zs, const int m[3],
                     double* f) {
  const int row = m[0], plane = m[0] * m[1];
  std::fill(f, f + plane * m[2], 0.0);
  for (const int32_t id : ids_) {
    const BlobSum::Blob& b = sum_->blobs()[size_t(id)];
    if (!(b.inv_r2 > 0)) {  // no ball: every point, a row at a time
      row_y_.resize(size_t(row));
      row_z_.resize(size_t(row));
      for (int k = 0; k < m[2]; ++k)
        for (int j = 0; j < m[1]; ++j) {
          std::fill(row_y_.begin(), row_y_.end(), ys[j]);
          std::fill(row_z_.begin(), row_z_.end(), zs[k]);
          add(id, xs, row_y_.data(), row_z_.data(), row, f + k * plane + j * row);
        }
      continue;
    }
    // values()'s sum (dx^2 + dy^2) + dz^2 is at least dy^2 + dz^2 as rounded (rounding is
    // monotone), so where (dy^2 + dz^2) s >= 1 every point of the row has r <= 0 and adds 0.
    const double cx = b.centre.x, cy = b.centre.y, cz = b.centre.z, s = b.inv_r2;
    const double c2 = b.c2, c3 = b.c3;
    for (int k = 0; k < m[2]; ++k) {
      const double dz = zs[k] - cz, dz2 = dz * dz;
      if (dz2 * s >= 1) continue;
      for (int j = 0; j < m[1]; ++j) {
        const double dy = ys[j] - cy, dy2 = dy * dy;
        if ((dy2 + dz2) * s >= 1) continue;
        double* out = f + k * plane + j * row;
        for (int i = 0; i < row; ++i) {
          const double dx = xs[i] - cx;
          const double r = 1 - (dx * dx + dy2 + dz2) * s;
          out[i] += r > 0 ? polynomial_potential(r, c2, c3) : 0.0;
        }
      }
    }
  }
}

double LeafBlobs::gradient(const Vec3& x, Vec3* grad) const {
  double f = 0;
  Vec3 g;
  for (const int32_t id : ids_) {
    const BlobSum::Blob& b = sum_->blobs()[size_t(id)];
    // A ball that clearly misses x (by a relative 1e-9, more than the two forms' rounding apart)
    // has r <= 0 in the frame's form too: skipped before its frame is read.
    if (b.inv_r2 > 0) {
      const Vec3 d = x - b.centre;
      if (dot(d, d) * b.inv_r2 > 1 + 1e-9) continue;
    }
    const BlobSum::Frame& frame = sum_->frames()[size_t(id)];
    const Vec3 w = frame.q(x);
    const double r = 1 - dot(w, w);
    if (!(r > 0)) continue;
    f += polynomial_potential(r, b.c2, b.c3);
    // dP/dr times ∇r = -2 L^T q.
    g += frame.transposed_times(w) * (-2 * polynomial_potential_slope(r, b.c2, b.c3));
  }
  *grad = g;
  return f;
}

}  // namespace softtrace

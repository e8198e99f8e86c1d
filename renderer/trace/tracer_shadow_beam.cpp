// ObjectTracer::shadow_beam: the blobs the shadow rays of a block of pixels may meet on their way
// to a directional light, listed once for the block, as tracer_blob_beam.cpp lists those its
// camera rays may meet. The rays are parallel and start at the block's lit points, so they run
// inside the prism over the rectangle that bounds those points seen along the light (ShadowPrism);
// the block's tile walks the sum's BVH once with the prism's four sides, and each smaller block
// keeps its parent's blobs whose bounding spheres reach into its own prism. A shadow ray of the
// block then finds each stretch's blobs by two comparisons per listed blob instead of a walk: the
// floor under the 1000-blob cloud cast 170,000 shadow rays, a quarter of them into the cloud's box,
// each paying at least one walk.
//
// Why it keeps every blob a ray of the block meets: a ray o + t along with o in the prism keeps
// o's x and y (u and v are orthogonal to `along`), so a point x of a blob's support on it has
// x's projection in the rectangle and lies in the blob's sphere (centre c, radius R): c's x and y
// are within R of the rectangle's, and x's z = z(o) + t >= z0 lies in [z(c) - R, z(c) + R].
// Rounding moves the ray's points by a few ulps of the coordinates (and u, v are orthogonal to
// `along` to a few ulps); every test has a slack of 1e-9 of the magnitudes involved, far above.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "trace/tracer.h"

namespace softtrace {

bool BlobBeam::holds_shadow(const Ray& ray, double* base) const {
  const ShadowPrism& p = prism;
  // The list's rays share their direction to the bit: a directional light's.
  if (ray.d.x != p.along.x || ray.d.y != p.along.y || ray.d.z != p.along.z) return false;
  const Vec3 q = ray.o - p.origin;
  const double x = dot(q, p.u), y = dot(q, p.v), z = dot(q, p.along);
  if (!(x >= p.x0 && x <= p.x1 && y >= p.y0 && y <= p.y1 && z >= p.z0)) return false;
  *base = z;
  return true;
}

void ObjectTracer::shadow_beam(const ShadowPrism& p, const BlobBeam* parent, BlobBeam* out) const {
  out->valid = false;
  out->parallel = true;
  out->prism = p;
  out->entries.clear();
  out->across.clear();
  if (!blobs_) return;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double span =
      std::max(std::max(std::abs(p.x0), std::abs(p.x1)), std::max(std::abs(p.y0), std::abs(p.y1)));
  const double magnitude = max_abs(p.origin) + span + std::abs(p.z0);
  const auto keep = [&](int32_t id) {
    Vec3 centre;
    const double r2 = blobs_->bounding_sphere(id, &centre);
    if (!(r2 < kInf)) {  // no sphere known: the blob stays on every ray's list
      out->entries.push_back({-kInf, kInf, id});
      out->across.push_back({0, 0, kInf});
      return;
    }
    const Vec3 q = centre - p.origin;
    const double r = std::sqrt(r2);
    const double reach = r + 1e-9 * (max_abs(q) + r + magnitude);
    const double x = dot(q, p.u), y = dot(q, p.v), z = dot(q, p.along);
    if (x < p.x0 - reach || x > p.x1 + reach || y < p.y0 - reach || y > p.y1 + reach ||
        z + reach < p.z0)
      return;
    out->entries.push_back({z - reach, z + reach, id});
    out->across.push_back({x, y, reach});
  };
  const auto same = [](const Vec3& a, const Vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  };
  const bool same_axes = parent && parent->valid && parent->parallel &&
                         same(parent->prism.origin, p.origin) &&
                         same(parent->prism.along, p.along) && same(parent->prism.u, p.u) &&
                         same(parent->prism.v, p.v);
  if (same_axes) {
    // The parent's prism has the same origin and axes: its numbers are what keep() would compute.
    for (size_t i = 0; i < parent->entries.size(); ++i) {
      const BlobBeam::Entry& e = parent->entries[i];
      const BlobBeam::Across& a = parent->across[i];
      if (a.x < p.x0 - a.reach || a.x > p.x1 + a.reach || a.y < p.y0 - a.reach ||
          a.y > p.y1 + a.reach || e.far < p.z0)
        continue;
      out->entries.push_back(e);
      out->across.push_back(a);
    }
  } else {
    // The prism's sides: x >= x0, x <= x1, y >= y0, y <= y1, each as dot(c - origin, n) >= -pad.
    const Vec3 normals[4] = {p.u, -p.u, p.v, -p.v};
    const double pad = 1e-9 * (scale_ + magnitude);
    const double pads[4] = {pad - p.x0, pad + p.x1, pad - p.y0, pad + p.y1};
    thread_local std::vector<int32_t> ids;
    if (static_cast<int>(ids.size()) < blobs_->size()) ids.resize(blobs_->size());
    const int found = blobs_->cone_items(program_, p.origin, normals, pads, ids.data());
    for (int i = 0; i < found; ++i) keep(ids[i]);
  }
  out->valid = true;
}

}  // namespace softtrace

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

#include "kernels/potentials.h"
#include "trace/tracer.h"
#include "trace/tracer_limits.h"

namespace softtrace {

bool BlobBeam::holds_shadow(const Ray& ray, double* base, double (*across)[2]) const {
  const ShadowPrism& p = prism;
  // The list's rays share their direction to the bit: a directional light's.
  if (ray.d.x != p.along.x || ray.d.y != p.along.y || ray.d.z != p.along.z) return false;
  const Vec3 q = ray.o - p.origin;
  const double x = dot(q, p.u), y = dot(q, p.v), z = dot(q, p.along);
  if (!(x >= p.x0 && x <= p.x1 && y >= p.y0 && y <= p.y1 && z >= p.z0)) return false;
  *base = z;
  if (across) {
    (*across)[0] = x;
    (*across)[1] = y;
  }
  return true;
}

// A toward list (render/shadow_beams.cpp builds it with blob_beam over the pyramid from the light,
// ShadowPrism) holds a ray from o inside the pyramid whose direction is (p - o) / |p - o| to a few
// ulps, p the pyramid's apex, over [0, t1] with t1 at most |p - o|: every point o + t d of it lies
// within 1e-14 |p - o| of the segment from o to p, which the pyramid holds (it is convex), at a
// distance from p within as much of |p - o| - t. With |o| at most 1e3 |p| (the largest
// coordinates), that is below 1e-10 |p|, far inside blob_beam's slack of 1e-9 |p| on every test.
bool BlobBeam::holds_toward(const Ray& ray, double t1, double* base) const {
  const ShadowPrism& p = prism;
  const double apex = max_abs(p.origin);
  if (!(max_abs(ray.o) <= 1e3 * apex)) return false;
  const Vec3 q = ray.o - p.origin;
  const double s = dot(q, p.along);
  if (!(s > 0)) return false;
  const double x = dot(q, p.u) / s, y = dot(q, p.v) / s;
  if (!(x >= p.x0 && x <= p.x1 && y >= p.y0 && y <= p.y1)) return false;
  const double distance = length(q);
  // Towards the apex (light_arrival's direction, to a few ulps), and not past it.
  if (!(max_abs(ray.d * distance + q) <= 1e-14 * distance)) return false;
  if (!(t1 <= distance * (1 + 1e-15))) return false;
  *base = -distance;
  return true;
}

namespace {
// Appends to `out` the parent list's entries, each with its Across, that `keeps(entry, across)`
// holds, in the parent's order: a child list (shadow_beam, toward_beam) is its parent's, thinned.
// The parent's size and data are read once: each push_back may, for all the compiler knows, write
// the parent's vectors, which made the loop reload its size every entry (meets10 at 320x240:
// 230,000 entries, 1.6 M instructions).
template <class Keeps>
[[gnu::always_inline]] inline void keep_from_parent(const BlobBeam& parent, Keeps keeps,
                                                    BlobBeam* out) {
  const size_t n = parent.entries.size();
  const BlobBeam::Entry* const entries = parent.entries.data();
  const BlobBeam::Across* const across = parent.across.data();
  for (size_t i = 0; i < n; ++i) {
    if (!keeps(entries[i], across[i])) continue;
    out->entries.push_back(entries[i]);
    out->across.push_back(across[i]);
  }
}
}  // namespace

void ObjectTracer::shadow_beam(const ShadowPrism& p, const BlobBeam* parent, BlobBeam* out) const {
  out->valid = false;
  out->clear = false;
  out->shut = false;
  out->parallel = true;
  out->toward = false;
  out->prism = p;
  out->entries.clear();
  out->across.clear();
  out->blockers.clear();
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
    // Behind the tile's points first: the cone walk's four sides do not see that, and it drops
    // 41 % of the blobs the walk returns to meets1's tiles at 640x480 (the sides, which the walk
    // tested, 4 %); the same blobs are kept, for the x and y of those behind not computed.
    const double z = dot(q, p.along);
    if (z + reach < p.z0) return;
    const double x = dot(q, p.u), y = dot(q, p.v);
    if (x < p.x0 - reach || x > p.x1 + reach || y < p.y0 - reach || y > p.y1 + reach) return;
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
    keep_from_parent(
        *parent,
        [&](const BlobBeam::Entry& e, const BlobBeam::Across& a) {
          return !(a.x < p.x0 - a.reach || a.x > p.x1 + a.reach || a.y < p.y0 - a.reach ||
                   a.y > p.y1 + a.reach || e.far < p.z0);
        },
        out);
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

// A toward list: a tile's pyramid takes blob_beam's list (its frustum from the light), whose
// distances from the light become minus them, and each blob's sphere on the pyramid's axes. A
// smaller pyramid on the same axes keeps its parent's blobs whose spheres reach inside its four
// side planes through the apex: the side x <= x1 s (s the depth) has the inside normal
// (x1 along - u) / h, h = sqrt(1 + x1^2), so a sphere (x, y, s; radius R) reaches into it where
// x - x1 s <= R h; and a blob that is no ball where its support does, as blob_beam tests it (the
// slack there is blob_beam's, from the distance and the radius, taken as the entry's range).
void ObjectTracer::toward_beam(const Frustum& f, const ShadowPrism& p, const BlobBeam* parent,
                               BlobBeam* out) const {
  const auto same = [](const Vec3& a, const Vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  };
  const bool narrow = parent && parent->valid && parent->toward &&
                      same(parent->prism.origin, p.origin) && same(parent->prism.along, p.along) &&
                      same(parent->prism.u, p.u) && same(parent->prism.v, p.v);
  out->parallel = false;
  out->toward = true;
  out->clear = false;
  out->shut = false;
  out->prism = p;
  out->blockers.clear();
  out->across.clear();
  if (!blobs_) {
    out->valid = false;
    out->entries.clear();
    return;
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!narrow) {
    blob_beam(f, nullptr, out);
    const double eye = max_abs(p.origin);
    for (BlobBeam::Entry& e : out->entries) {
      e = {-e.far, -e.near, e.id};  // the axis grows along the rays
      Vec3 centre;
      const double r2 = blobs_->bounding_sphere(e.id, &centre);
      if (!(r2 < kInf)) {
        out->across.push_back({0, 0, kInf, 0});
        continue;
      }
      const Vec3 q = centre - p.origin;
      const double r = std::sqrt(r2);
      const double reach = r + 1e-9 * (length(q) + r + eye);
      out->across.push_back({dot(q, p.u), dot(q, p.v), reach, dot(q, p.along)});
    }
    return;
  }
  out->valid = false;
  out->entries.clear();
  out->eye = p.origin;
  const double hx0 = std::sqrt(1 + p.x0 * p.x0), hx1 = std::sqrt(1 + p.x1 * p.x1),
               hy0 = std::sqrt(1 + p.y0 * p.y0), hy1 = std::sqrt(1 + p.y1 * p.y1);
  const Vec3 normals[4] = {(p.u - p.along * p.x0) / hx0, (p.along * p.x1 - p.u) / hx1,
                           (p.v - p.along * p.y0) / hy0, (p.along * p.y1 - p.v) / hy1};
  const double eye = max_abs(p.origin);
  keep_from_parent(
      *parent,
      [&](const BlobBeam::Entry& e, const BlobBeam::Across& a) {
        if (!(a.reach < kInf)) return true;
        if (a.x - p.x1 * a.depth > a.reach * hx1 || p.x0 * a.depth - a.x > a.reach * hx0 ||
            a.y - p.y1 * a.depth > a.reach * hy1 || p.y0 * a.depth - a.y > a.reach * hy0)
          return false;
        if (!blobs_->is_framed(e.id)) return true;
        // blob_beam's slack, 1e-9 (distance + r + eye), with the range's half-width for r.
        const double slack = 1e-9 * (-0.5 * (e.near + e.far) + 0.5 * (e.far - e.near) + eye);
        bool outside = false;
        for (const Vec3& n : normals)
          outside = outside || blobs_->support_extent(e.id, n) - dot(n, p.origin) < -slack;
        return !outside;
      },
      out);
  out->valid = true;
}

// Blockers. The blobs of a sum of positive blobs are non-negative terms, so where one blob's own
// potential exceeds iso, so does the field: a shadow ray passing near enough to one ball's centre
// is blocked whatever the others do. Most shadow rays under the 1000-blob cloud (the floor's in
// its shadow) pass that near a ball; found by the stretches, each cost a query, the terms of its
// blobs, the events' sort and the pieces before the first one that decided.
namespace {
// A block keeps at most this many blockers (the first one usually decides its rays).
constexpr int kBlockers = 2;
}  // namespace

void ObjectTracer::shadow_blockers(BlobBeam* list) const {
  list->blockers.clear();
  list->shut = false;
  if (!blobs_ || !list->valid || !(list->parallel || list->toward)) return;
  const ShadowPrism& p = list->prism;
  // A ball is picked (below) only where its r at the rectangle's farthest corner, 1 - (dx^2 +
  // dy^2) / R^2, lifts it above iso; dx and dy are at least the rectangle's half-sides, so none is
  // where their squares' sum reaches blocker_reach2 (the rounding of both sides is a few ulps, 1e-9
  // spares far more), and the list keeps no blocker and is not shut, as the loop would find. A
  // tile's or a quarter's list asked by shut_and_lend whose prism is wider than the sum's widest
  // blocker then costs no loop over its entries (meets1 at 320x240: this function 5.14 -> 0.12 M).
  if (list->parallel) {
    const double hx = 0.5 * (p.x1 - p.x0), hy = 0.5 * (p.y1 - p.y0);
    if (!((hx * hx + hy * hy) * (1 - 1e-9) < blocker_reach2_)) return;
  }
  const std::vector<BlobSum::Blob>& blobs = blobs_->blobs();
  const double iso = target_.iso;
  // The rounding of a piece's polynomial (stretch_polynomial's err): (128 + n) ulps of the sum of
  // its terms' magnitudes, each at most |c2| m^2 + |c3| m^3 with m = |R0| + |R1| + |R2| <= 9 over
  // a piece inside the support (R0 <= h2 <= 1, |R1| and R2 at most 4 h2), and n at most three
  // terms (a capsule's) per listed blob. Twice that.
  double magnitude = iso;
  int32_t best[kBlockers];
  double best_z[kBlockers];
  size_t best_i[kBlockers];
  int picked = 0;
  for (size_t i = 0; i < list->entries.size(); ++i) {
    const BlobBeam::Entry& e = list->entries[i];
    const BlobSum::Blob& b = blobs[e.id];
    // A negative blob may cancel a blocker's potential: no blob certifies alone.
    if (!(b.c2 >= 0 && b.c3 >= 0)) return;
    magnitude += 3 * (100 * b.c2 + 1000 * b.c3);
    if (!(b.inv_r2 > 0)) continue;  // only balls: the rays' nearest points are the across ones
    // With kBlockers picked, a ball no farther towards the light than the last of them would not
    // be taken (below): its test is skipped (a floor block's list under the 1000-blob cloud holds
    // ~35 blobs; this function's instructions on that frame fell from 25.4 to 22.6 M).
    const double z = 0.5 * (e.near + e.far);
    if (picked == kBlockers && !(best_z[kBlockers - 1] < z)) continue;
    // A choice, not a certificate (blocked_by decides each ray): a ball whose potential at the
    // rectangle's farthest corner from its centre is above iso by 1e-3 of it. A pyramid's
    // rectangle is its section at the centre's depth (a ball behind the apex is none).
    double dx, dy;
    if (list->parallel) {
      const BlobBeam::Across& a = list->across[i];
      dx = std::max(std::abs(a.x - p.x0), std::abs(a.x - p.x1));
      dy = std::max(std::abs(a.y - p.y0), std::abs(a.y - p.y1));
    } else {
      const Vec3 q = b.centre - p.origin;
      const double depth = dot(q, p.along), x = dot(q, p.u), y = dot(q, p.v);
      if (!(depth > 0)) continue;
      dx = std::max(std::abs(x - p.x0 * depth), std::abs(x - p.x1 * depth));
      dy = std::max(std::abs(y - p.y0 * depth), std::abs(y - p.y1 * depth));
    }
    const double r = 1 - (dx * dx + dy * dy) * b.inv_r2;
    if (!(r > 0 && polynomial_potential(r, b.c2, b.c3) > iso * (1 + 1e-3))) continue;
    // The ones farthest towards the light (a pyramid's axis is minus the distance from it): most
    // likely ahead of rays that start inside the cloud.
    int k = picked < kBlockers ? picked++ : kBlockers;
    while (k > 0 && best_z[k - 1] < z) {
      if (k < kBlockers)
        best[k] = best[k - 1], best_z[k] = best_z[k - 1], best_i[k] = best_i[k - 1];
      --k;
    }
    if (k < kBlockers) best[k] = e.id, best_z[k] = z, best_i[k] = i;
  }
  const double n = 3.0 * static_cast<double>(list->entries.size());
  list->blockers_err = 2 * (128 + n) * std::numeric_limits<double>::epsilon() * magnitude;
  list->blockers.assign(best, best + picked);
  if (list->parallel)
    for (int k = 0; k < picked && !list->shut; ++k) shut_by(list, best_i[k]);
}

// A ball (c2, c3 >= 0, radius R) is picked only where P(r) = r^2 (c2 + c3 r) > iso at r = 1 -
// s / R^2, s the square distance across: P increases on [0, 1], so r must exceed lo, the
// bisection's last point with P(lo) <= iso (1 - 1e-9), below the root even after P's rounding, and
// s must be below R^2 (1 - lo) (1e-12 more for the rounding of 1 - s / R^2 when lo is near 1). The
// sum's balls mostly share their strengths: a ball like the one before takes its lo (1000 balls' 30
// bisection steps each would cost a 1000-blob scene 0.3 M instructions).
double ObjectTracer::blocker_reach2(const BlobSum& sum, double iso) {
  const double below = iso * (1 - 1e-9);
  double widest = 0, c2 = -1, c3 = -1, lo = 1;
  for (const BlobSum::Blob& b : sum.blobs()) {
    if (!(b.inv_r2 > 0 && b.c2 >= 0 && b.c3 >= 0)) continue;
    if (b.c2 != c2 || b.c3 != c3) {
      c2 = b.c2, c3 = b.c3, lo = 1;
      if (polynomial_potential(1, c2, c3) > below) {
        double hi = 1;
        lo = 0;
        for (int i = 0; i < 30; ++i) {
          const double mid = 0.5 * (lo + hi);
          (polynomial_potential(mid, c2, c3) <= below ? lo : hi) = mid;
        }
      }
    }
    if (lo < 1) widest = std::max(widest, (1 - lo + 1e-12) / b.inv_r2);
  }
  return widest;
}

// Shut blocks. blocked_by decides a ray by one ball's term alone, as a per-ray check: most of a
// floor's rays under a cloud pass it, 4 to a block, each paying the term, its footprints and
// square roots. Where a picked blocker passes blocked_by's test for every ray the block may send,
// with margins that no rounding of it can eat, the block is shut: its rays take blocked_by's
// answer (a hit, one point evaluation) with no term (first_hit_blobs, shut_decides). What each
// ray still checks itself: that the list holds it and it starts at z <= z1 (so it is one of the
// rays below), and blocked_by's two footprint conditions, at the box's entry t0 and exit t1.
//
// The rays: direction d = along (holds: to the bit), origins o with x in [x0, x1], y in [y0, y1]
// (to the rounding of holds' dot products) and z in [z0, z1]. The ball: centre c at (x, y, z) on
// the prism's axes, radius R, potential P(r) = r^2 (c2 + c3 r), r = 1 - |q - c|^2 / R^2, P
// increasing on [0, 1] (c2, c3 >= 0: shadow_blockers keeps none where any listed blob is
// negative). A ray's nearest approach to c is in the plane z, at a distance in the rectangle's
// plane at most its farthest corner's (dx, dy), so its term's h2 >= r_c = 1 - (dx^2 + dy^2) / R^2
// less rounding (eps1: 1e-9 and 64 ulps of |o - c|^2 / R^2). With delta = 1e-4 and
// r_lo = r_c - delta - eps1, and alpha = |d|^2 / R^2:
// - the footprint bound keeps alpha w^2 <= delta / 4 (w = blocked_by's half-width), so
//   r(mid +- w) >= h2 - delta / 4 and r(mid +- 2w) >= h2 - delta >= r_lo;
// - r_lo >= delta: the support's half-chord sqrt(h2 / alpha) >= 2w, and the points
//   mid +- 2w lie within R sqrt(1 - r_lo) of c, a ball the object's box holds with a margin
//   (checked): the ray enters the box before mid - 2w and leaves it after mid + 2w, so the term's
//   enter <= mid - 2w and exit >= mid + 2w, blocked_by's u is mid, and exit - enter > 2w;
// - c lies at least 2 R sqrt(delta) >= 4w beyond z1 along the rays: mid - 2w is past t = 0 too;
// - blocked_by's dr (from the box's diagonal and the coordinates' magnitudes) is at most
//   delta / 4 (checked), so r - dr >= r_lo + delta / 2 at u +- w, rounded by far less;
// - P(r_lo) - iso exceeds twice blockers_err and the rounding of P's evaluation.
// So blocked_by returns a point for every such ray: this blocker's, or an earlier one's.
void ObjectTracer::shut_by(BlobBeam* list, size_t i) const {
  constexpr double kDelta = 1e-4;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const ShadowPrism& p = list->prism;
  const BlobSum::Blob& b = blobs_->blobs()[list->entries[i].id];
  const BlobBeam::Across& a = list->across[i];
  const Box& box = target_.bounds;
  const double dx = std::max(std::abs(a.x - p.x0), std::abs(a.x - p.x1));
  const double dy = std::max(std::abs(a.y - p.y0), std::abs(a.y - p.y1));
  const double diagonal = length(box.hi - box.lo) * (1 + 1e-9);
  const double far = 2.01 * diagonal;  // |o - c| + the way's length, o and c in the box
  const double eps1 = 1e-9 + 64 * eps * far * far * b.inv_r2;
  const double r_lo = 1 - (dx * dx + dy * dy) * b.inv_r2 - kDelta - eps1;
  if (!(r_lo >= kDelta)) return;
  const double potential = polynomial_potential(r_lo, b.c2, b.c3);
  if (!(potential - target_.iso > 2 * list->blockers_err + 1e-12 * (b.c2 + b.c3 + target_.iso)))
    return;
  // Ahead of every ray's origin.
  const double radius = std::sqrt(1 / b.inv_r2);
  const double magnitude = max_abs(p.origin) + max_abs(b.centre) + radius;
  const double z = dot(b.centre - p.origin, p.along);
  if (!(z - p.z1 >= 2 * radius * std::sqrt(kDelta) * (1 + 1e-9) + 1e-9 * magnitude)) return;
  // Inside the box, with the clip's rounding to spare.
  const double inner =
      radius * std::sqrt(1 - r_lo + 1e-9) + 1e-9 * (max_abs(box.lo) + max_abs(box.hi) + magnitude);
  const Vec3& c = b.centre;
  if (!(c.x - inner >= box.lo.x && c.y - inner >= box.lo.y && c.z - inner >= box.lo.z &&
        c.x + inner <= box.hi.x && c.y + inner <= box.hi.y && c.z + inner <= box.hi.z))
    return;
  // blocked_by's dr: far as above, its reach (|o| + |t0| + |t1|) from the rays' origins (within
  // the prism's rectangle and depths) and their ways to the box's far side.
  const double origins = max_abs(p.origin) + std::max(std::abs(p.x0), std::abs(p.x1)) +
                         std::max(std::abs(p.y0), std::abs(p.y1)) +
                         std::max(std::abs(p.z0), std::abs(p.z1));
  const double reach =
      (origins + 2 * std::sqrt(3.0) * (origins + max_abs(box.lo) + max_abs(box.hi))) * (1 + 1e-6);
  const double dr = 1e-6 + 1e-12 * far * far * b.inv_r2 + 1e-9 * std::sqrt(3 * b.inv_r2) * reach;
  if (!(dr <= kDelta / 4)) return;
  // alpha w^2 <= delta / 4, w = 2 kFinestDeep kDecide footprint.
  using namespace tracer_limits;
  const double alpha = dot(p.along, p.along) * b.inv_r2;
  list->shut_footprint = 0.999 * std::sqrt(kDelta / (4 * alpha)) / (2 * kFinestDeep * kDecide);
  list->shut = list->shut_footprint > 0;
}

bool ObjectTracer::shut_decides(const Ray& ray, double t0, double t1, double base,
                                const BlobBeam& list) const {
  using namespace tracer_limits;
  const double finest = kFinestDeep * kDecide;
  return base <= list.prism.z1 && footprint(ray, t1) <= list.shut_footprint &&
         t1 - t0 < 0x1p60 * finest * footprint(ray, t0);
}

std::optional<double> ObjectTracer::blocked_by(const Ray& ray, double t0, double t1,
                                               const BlobBeam& list) const {
  using namespace tracer_limits;
  const double iso = target_.iso;
  // The search halves a piece down to kFinestDeep of its tolerance, kDecide footprints at the
  // piece's start (between the footprints at t0 and t1: it grows along the ray), and no further
  // than its stack's 64 levels allow (a piece is at most t1 - t0 long). A stretch of at least
  // twice that where the field is above iso holds the end of a finest piece, whose last Bernstein
  // coefficient is the polynomial's value there (a Bracket), or the start of a piece (AtStart),
  // unless the search found a crossing before it: either way a hit. Such a stretch here is
  // [u - w, u + w].
  const double finest = kFinestDeep * kDecide;
  const double w = 2 * finest * footprint(ray, t1);
  if (!(t1 - t0 < 0x1p60 * finest * footprint(ray, t0))) return std::nullopt;
  const Vec3 o = segment(ray, t0, t1).a;
  const double len = t1 - t0, reach = max_abs(ray.o) + std::abs(t0) + std::abs(t1);
  // A ball's term inline (terms_of_one: terms_of's arithmetic for one blob, so the same bits);
  // terms_of's call for each blocker was 4.8 M of pov:chain's instructions at 640x480, most of
  // them for lit rays, which no blocker holds.
  const double dd = dot(ray.d, ray.d);
  for (const int32_t id : list.blockers) {
    BlobSum::Term term;
    if (blobs_->terms_of_one(id, o, ray.d, dd, len, &term) != 1) continue;  // a ball: one term
    if (!(term.exit - term.enter > 2 * w)) continue;
    const BlobSum::Blob& b = blobs_->blobs()[id];
    // What separates r here from r as a stretch computes it from its own start (BlobSum::span's
    // eps, with the stretch's start anywhere in [t0, t1]), taken off r.
    const Vec3 oc = o - b.centre;
    const double far = length(oc) + len;
    const double dr = 1e-6 + 1e-12 * far * far * b.inv_r2 + 1e-9 * std::sqrt(3 * b.inv_r2) * reach;
    const double u = std::clamp(term.mid, term.enter + w, term.exit - w);
    bool above = true;
    for (const double x : {u - w, u + w}) {  // r is concave along the ray: its least at an end
      const double r = term.h2 - term.alpha * (x - term.mid) * (x - term.mid) - dr;
      above = above && r > 0 && polynomial_potential(r, term.c2, term.c3) - iso > list.blockers_err;
    }
    if (above) return t0 + u;
  }
  return std::nullopt;
}

}  // namespace softtrace

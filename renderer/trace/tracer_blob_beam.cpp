// ObjectTracer::blob_beam: the blobs a block of camera rays may meet, listed once for the block
// (the tile-level active list of Zanni's Synchronized Tracing, 2025). A ray of the block then
// takes its blobs from the list by their ranges of distances from the eye instead of a walk of
// the sum's BVH, whose node tests were a third of a dense cloud's frame: a larger sum's list is
// sorted by the ranges' near ends, and its rays sweep it front to back (tracer_blobs.cpp).
// A tile's list comes from one walk of the BVH with the frustum's side planes; each quarter of it
// keeps the parent's blobs whose bounding spheres meet its own frustum.
//
// Why it keeps every blob a ray of the block meets: a point x of a blob's support lies in its
// sphere (centre c, radius R), and a ray from the eye through the block lies inside the frustum
// (its direction is a convex combination of the corners'), at distance t = |x - eye| from the eye
// (d has unit length). So the sphere reaches inside every side plane, and t lies in
// [|c - eye| - R, |c - eye| + R]; for a blob that is no ball, the support itself reaches inside
// every side plane (n.x >= n.eye), so its support function there does. Rounding moves the ray's
// points by a few ulps of |eye| + t; every test has a slack of 1e-9 of the magnitudes involved, far
// above that.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "trace/blob_beam_lanes.h"
#include "trace/tracer.h"

namespace softtrace {

namespace {
// The frustum's four side planes through the eye, with unit normals pointing inside (a zero
// normal where two corners coincide: that plane then cuts nothing).
void side_normals(const Frustum& f, Vec3 (&normals)[4]) {
  // corner[0..3] are the rectangle's (x0, y0), (x1, y0), (x0, y1), (x1, y1): around it 0, 1, 3, 2.
  static constexpr int kAround[5] = {0, 1, 3, 2, 0};
  const Vec3 middle = f.corner[0] + f.corner[1] + f.corner[2] + f.corner[3];
  for (int i = 0; i < 4; ++i) {
    Vec3 n = cross(f.corner[kAround[i]], f.corner[kAround[i + 1]]);
    const double len = length(n);
    if (!(len > 0)) {
      normals[i] = {0, 0, 0};
      continue;
    }
    if (dot(n, middle) < 0) n = -n;
    normals[i] = n / len;
  }
}
}  // namespace

void ObjectTracer::blob_beam(const Frustum& f, const BlobBeam* parent, BlobBeam* out,
                             bool passable) const {
  out->valid = false;
  out->entries.clear();
  out->sifted = false;
  out->adders.clear();
  out->passing = 0;
  out->passing_framed = 0;
  if (!blobs_) return;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 normals[4];
  side_normals(f, normals);
  const BeamSides sides{f.eye, {normals[0], normals[1], normals[2], normals[3]}, max_abs(f.eye)};
  const std::vector<BlobSum::Blob>& blobs = blobs_->blobs();
  const auto keep = [&](int32_t id) {
    if (!blobs_->is_framed(id) && 1 / blobs[id].inv_r2 < kInf) {
      double near, far;
      if (ball_in_beam(blobs[id], sides, &near, &far)) out->entries.push_back({near, far, id});
      return;
    }
    Vec3 centre;
    const double r2 = blobs_->bounding_sphere(id, &centre);
    if (!(r2 < kInf)) {  // no sphere known: the blob stays on every ray's list
      out->entries.push_back({-kInf, kInf, id});
      return;
    }
    const double r = std::sqrt(r2);
    const Vec3 v = centre - f.eye;
    const double distance = length(v);
    const double slack = 1e-9 * (distance + r + sides.eye_scale);
    for (const Vec3& n : normals)
      if (dot(v, n) < -r - slack) return;
    // A blob that is no ball: its support's own extent past each plane (its outline's support
    // function, BlobSum::support_extent; +inf where none is known). A long capsule's sphere meets
    // most frusta its support misses (pov:blob1b: 14-unit capsules across the whole frame).
    if (blobs_->is_framed(id))
      for (const Vec3& n : normals)
        if (blobs_->support_extent(id, n) - dot(n, f.eye) < -slack) return;
    out->entries.push_back({distance - r - slack, distance + r + slack, id});
  };
  // The blobs ids[0, n) in order, four balls at a time where four come together (a cloud's are
  // all balls; blob_beam_lanes.h gives ball_in_beam's bits in each lane): the same entries in the
  // same order as keep() one at a time.
  const BallsInBeam four_balls = balls_in_beam();
  const auto keep_all = [&](const int32_t* ids, int n) {
    int i = 0;
    for (; i + 4 <= n; i += 4) {
      const int32_t four[4] = {ids[i], ids[i + 1], ids[i + 2], ids[i + 3]};
      if (blobs_->is_framed(four[0]) || blobs_->is_framed(four[1]) || blobs_->is_framed(four[2]) ||
          blobs_->is_framed(four[3])) {
        for (const int32_t id : four) keep(id);
        continue;
      }
      const BlobSum::Blob* const lanes[4] = {&blobs[four[0]], &blobs[four[1]], &blobs[four[2]],
                                             &blobs[four[3]]};
      double near[4], far[4];
      const unsigned in = four_balls(lanes, sides, near, far);
      if (in >> 4) {  // a radius not finite: keep() takes such a ball as no sphere known
        for (const int32_t id : four) keep(id);
        continue;
      }
      for (int k = 0; k < 4; ++k)
        if (in >> k & 1) out->entries.push_back({near[k], far[k], four[k]});
    }
    for (; i < n; ++i) keep(ids[i]);
  };
  thread_local std::vector<int32_t> ids;
  if (static_cast<int>(ids.size()) < blobs_->size()) ids.resize(blobs_->size());
  if (parent && parent->from(f.eye)) {
    const int n = static_cast<int>(parent->entries.size());
    for (int i = 0; i < n; ++i) ids[i] = parent->entries[i].id;
    keep_all(ids.data(), n);
  } else {
    const int found =
        blobs_->cone_items(program_, f.eye, normals, 1e-9 * (scale_ + sides.eye_scale), ids.data());
    keep_all(ids.data(), found);
    // A larger sum's camera rays sweep the list in this order (tracer_blobs.cpp); a quarter's,
    // kept from it in order with the same distances, stays so. A toward list (toward_beam, which
    // marks `out` before calling here) keeps the walk's order: its shadow rays take their terms
    // in the list's order, as a list-less ray takes them from the BVH, to the bit.
    if (out->camera() && blobs_->size() > BlobSum::kListed)
      std::sort(out->entries.begin(), out->entries.end(),
                [](const BlobBeam::Entry& a, const BlobBeam::Entry& b) {
                  return a.near < b.near || (a.near == b.near && a.id < b.id);
                });
  }
  if (out->camera() && blobs_->size() > BlobSum::kListed && blobs_->subtracts()) {
    const int n = static_cast<int>(out->entries.size());
    for (int i = 0; i < n; ++i)
      if (blobs_->adds(out->entries[i].id)) out->adders.push_back(i);
    out->sifted = static_cast<int>(out->adders.size()) < n;
  }
  // Only for a block whose rays ask passes_listed_balls: a tile's and a quarter's lists, which no
  // ray reads, took 0.29 M of its 1.18 M instructions (meets1 640x480).
  if (passable) passing_balls(f, sides.eye_scale, out);
  out->eye = f.eye;
  out->valid = true;
}

// A ray that passes a ball's centre c at distance D (the line's, d of unit length) has at most
// the term h2 = 1 - D^2 / r^2 there (BlobSum::ball_term: none where h2 <= 0), and its peak,
// P(r) = r^2 (c2 + c3 r) at r <= h2 (Term::peak), is at most h2^2 (|c2| + |c3|), as r <= 1. A
// ray whose bounds sum below iso is read as first_hit_blobs reads it: each piece's peaks sum
// below iso (its first test, which every piece then fails), so no piece is counted or searched,
// and each stretch ends as an empty list's, counted, the next no shorter than what is left (as
// unlisted_stretches; at most kPassable < kManyTerms terms). With b = (eye - c).d, D^2 =
// |eye - c|^2 - b^2, here from the block's eye - c. What bounds the rounding, all in k, as
// multiples of |eye - c|^2 / r^2: this D^2's (its cancellation, and d's length, 1 to a few ulps)
// at most a few ulps of |eye - c|^2; the sweep's, from its stretch's start, on the line to a few
// ulps of |eye| + t0 (t0 <= |eye - c| + r, or the ball's entry is skipped), at most a few ulps
// of (|eye| + 3 |eye - c| + r) |eye - c|; 1e-11 is thousands of ulps. Then 1e-12 for h2's own.
// A blob that only subtracts (BlobSum::adds) gives terms whose peaks are 0, so it adds nothing to
// any piece's peak sum: it takes no bound, whatever its shape (pov:old_syntax's negative ball
// among three positive ones).
//
// A capsule or an ellipsoid (a frame: r = 1 - |q|^2, q = L x + k less its nearest point s axis,
// s in [0, 1]; axis = 0 for an ellipsoid): along the ray, L x + k = q0 + t w with q0 = L eye + k
// and w = L d, so r <= 1 - D^2, D the distance from that line to the segment [0, axis], which is
// the distance from q0 to the segment [0, axis] both taken across w (passes_listed_balls). Each
// of its up to three terms (its end balls' and its middle's) then peaks at most (1 - D^2)^2
// (|c2| + |c3|), and a piece holds at most one of them (their ranges only touch, and of equal
// events exits come first: blob_events.h). The rounding: the sweep's w and v come from the
// stretch's start, within eye + (|eye - c| + R) d of a term's blob (c, R its bounding sphere),
// and each r errs by a few ulps of (1 + |w|^2 + |axis|^2) (blob_frame_terms.h); this D^2 by a
// few ulps of (|q0| + |axis|)^2. Both are below a few ulps of the square of scale = 1 +
// |L|_F (|eye| + |eye - c| + R) + |k| + |axis|, and 1e-11 of that is thousands of ulps.
//
// A list with a capsule or an ellipsoid keeps its passes only where a ray through one of the
// block's corners passes: their test costs a ray some 100 instructions, and where a block lies
// within such a blob's silhouette none of its rays passes (pov:blob1a, whose two capsules of
// radius 4 cross the frame: +2.3 % of its process with every block's rays tested). A choice,
// not a certificate: each ray of a passable block is still tested on its own.
void ObjectTracer::passing_balls(const Frustum& f, double eye_scale, BlobBeam* out) const {
  if (!out->camera() || out->entries.size() > size_t(BlobBeam::kPassable)) return;
  const Vec3& eye = f.eye;
  const std::vector<BlobSum::Blob>& blobs = blobs_->blobs();
  // Balls first, then the framed blobs (passes_listed_balls' two loops).
  BlobBeam::Passing framed[BlobBeam::kPassable];
  int n = 0, n_framed = 0;
  for (const BlobBeam::Entry& e : out->entries) {
    if (!blobs_->adds(e.id)) continue;
    const BlobSum::Blob& b = blobs[e.id];
    const double mag = std::abs(b.c2) + std::abs(b.c3);
    if (blobs_->is_framed(e.id)) {
      const BlobSum::Frame& frame = blobs_->frames()[e.id];
      Vec3 c;
      const double reach2 = blobs_->bounding_sphere(e.id, &c);
      if (!std::isfinite(reach2)) return;
      const double norm =
          std::sqrt(dot(frame.L.r[0], frame.L.r[0]) + dot(frame.L.r[1], frame.L.r[1]) +
                    dot(frame.L.r[2], frame.L.r[2]));
      const double scale = 1 + norm * (length(eye) + length(eye - c) + std::sqrt(reach2)) +
                           length(frame.k) + length(frame.axis);
      if (!std::isfinite(scale)) return;
      BlobBeam::Passing& pass = framed[n_framed++];
      pass.oc = frame.times(eye) + frame.k;
      pass.k = 1e-11 * scale * scale;
      pass.frame = e.id;
      pass.mag = mag;
      continue;
    }
    if (!(b.inv_r2 > 0)) return;
    const Vec3 oc = eye - b.centre;
    const double oc2 = dot(oc, oc);
    const double w = 0.5 * (e.far - e.near);  // r and blob_beam's slack
    const double rounding = 1e-11 * (oc2 + (eye_scale + w) * std::sqrt(oc2)) * b.inv_r2 + 1e-12;
    out->passes[n++] = {oc, 1 - oc2 * b.inv_r2 + rounding, {b.inv_r2}, mag};
  }
  for (int i = 0; i < n_framed; ++i) out->passes[n++] = framed[i];
  out->passing = n;
  out->passing_framed = n_framed;
  if (n_framed == 0) return;
  for (const Vec3& corner : f.corner)
    if (passes_listed_balls({eye, normalize(corner), 0, 0}, *out)) return;
  out->passing = 0;
  out->passing_framed = 0;
}

bool ObjectTracer::passes_listed_balls(const Ray& ray, const BlobBeam& list) const {
  // d of unit length to a few ulps, as k assumes (a camera ray's is normalised).
  if (!(std::abs(dot(ray.d, ray.d) - 1) < 1e-14)) return false;
  double peaks = 0;
  const int balls = list.passing - list.passing_framed;
  for (int i = 0; i < balls; ++i) {
    const BlobBeam::Passing& p = list.passes[i];
    const double b = dot(p.oc, ray.d);
    const double h2 = p.k + b * b * p.inv_r2;
    if (h2 > 0) peaks += h2 * h2 * p.mag;
  }
  for (int i = balls; i < list.passing; ++i) {
    // q0 and the axis across w = L d: their distance is D (passing_balls).
    const BlobBeam::Passing& p = list.passes[i];
    const BlobSum::Frame& f = blobs_->frames()[p.frame];
    const Vec3 w = f.times(ray.d);
    const double ww = dot(w, w);
    if (!(ww > 0)) return false;
    const Vec3 q = p.oc - w * (dot(p.oc, w) / ww), axis = f.axis - w * (dot(f.axis, w) / ww);
    const double aa = dot(axis, axis);
    const double s = aa > 0 ? std::clamp(dot(q, axis) / aa, 0.0, 1.0) : 0.0;
    const Vec3 gap = q - axis * s;
    const double h2 = 1 - dot(gap, gap) + p.k;
    if (h2 > 0) peaks += h2 * h2 * p.mag;
  }
  // Far above the sum's and the pieces' own rounding (first_hit_blobs: 1e-12 of it, 1e-15 a term).
  return peaks * (1 + 1e-9) + 1e-9 < target_.iso;
}

}  // namespace softtrace

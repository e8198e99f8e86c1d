// A sum of polynomial blobs along a ray, as POV-Ray's blob solves it. Murakami's, Wyvill's and the
// cubic potentials are polynomials in r = 1 - d^2 (r^2, (5 r^2 + 4 r^3)/9 and r^3, docs/math.md
// §3.3-§3.4), and
// an ellipsoidal distance's d^2 is quadratic along a line. A capsule's (the distance to a segment,
// POV-Ray's cylinder component) is quadratic on each of three parts of the line: before the plane
// through one end perpendicular to the segment (the distance to that end), between the two planes
// (to the segment's line) and beyond the other (to the other end). So between the points where a
// ray enters and leaves those parts of the blobs' supports, a soft_blend of such soft objects is
// one polynomial of degree at most 6 in t, which bernstein.h decides exactly, with no Lipschitz
// bound and no step.
//
// Along the ray x = o + u d, a blob whose support is |L x + k| <= 1 has d^2 = q(u) = 1 - h2 +
// alpha (u - mid)^2 (mid the point nearest its centre, h2 = 1 - q(mid)), hence r = h2 - alpha
// (u - mid)^2: three numbers per blob and ray, well conditioned however far the ray starts. A
// capsule's three parts are three such terms, each over its own part of the ray.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "kernels/potentials.h"
#include "math/bernstein.h"
#include "program/program.h"

namespace softtrace {

class BlobSum {
 public:
  // The blobs of `p` if its field is exactly a sum of soft objects, each Murakami's, Wyvill's or
  // the cubic potential of an lp_metric with n = 2 or of a segment, under any placement, of any
  // strength; nullopt otherwise.
  static std::optional<BlobSum> of(const Program& p);

  // One blob's part of a stretch of ray (a capsule has up to three): its potential is P(r(u))
  // over [enter, exit] (the support clipped to the stretch, and for a capsule to one side of, or
  // between, its end planes), r(u) = h2 - alpha (u - mid)^2, P(r) = c2 r^2 + c3 r^3.
  struct Term {
    double enter, exit;
    double mid, alpha, h2;
    double c2, c3;
    double peak;  // an upper bound of P's values over [enter, exit] (0 for a negative strength)
  };
  // The terms of the blobs whose supports the stretch o + u d, u in [0, len], passes through (d a
  // unit vector; `pad` the rounding of the points the caller will take along it), in out[];
  // returns their number. `ids` needs room for size() entries, `out` for max_terms().
  int terms(const Program& p, const Vec3& o, const Vec3& d, double len, double pad, Term* out,
            int32_t* ids) const;
  // The same from the blobs ids[0, found) instead of the query, which must hold every blob whose
  // support the stretch passes through, in the order the query reports them (the sum's BVH's
  // tree order: then the terms, and the sums made of them, are the same to the bit).
  int terms_of(const int32_t* ids, int found, const Vec3& o, const Vec3& d, double len,
               Term* out) const;
  // terms_of for the one blob `id`, with dd = dot(d, d): a ball's term inline, the same
  // arithmetic and so the same bits. A camera ray's sweep takes its list's blobs one at a time
  // (tracer_blobs.cpp); a call of terms_of per blob cost 4.3 % of blob1000's process at 640x480.
  int terms_of_one(int32_t id, const Vec3& o, const Vec3& d, double dd, double len,
                   Term* out) const {
    const Blob& b = blobs_[id];
    if (b.inv_r2 > 0) return ball_term(b, o, d, dd, len, out);
    return frame_terms(id, o, d, len, out);
  }
  // The blobs whose support boxes meet the pyramid of cone_items (math/bvh.h), in that tree
  // order; for a sum of at most kListed blobs, which have no BVH query, all of them in the order
  // terms() takes them.
  int cone_items(const Program& p, const Vec3& apex, const Vec3 (&normals)[4], double pad,
                 int32_t* out) const;
  // The same for the half-spaces dot(x - apex, normals[i]) >= -pads[i] (BoxBvh::cone_items).
  int cone_items(const Program& p, const Vec3& apex, const Vec3 (&normals)[4],
                 const double (&pads)[4], int32_t* out) const;
  // A sphere holding blob `id`'s support: its centre and squared radius (+inf where no sphere is
  // known: BlobSum::Blob's reach2).
  double bounding_sphere(int id, Vec3* centre) const {
    const Blob& b = blobs_[id];
    *centre = b.centre;
    return b.inv_r2 > 0 ? 1 / b.inv_r2 : b.reach2;
  }
  // f(x) and ∇f(x) from the blobs whose supports hold x (∇ of c2 r^2 + c3 r^3 with r = 1 - |q|^2,
  // q = Lx + k less its nearest point of the axis): the compiled gradient's value without pruning
  // the program first. `ids` as for terms. With `terms`, the program's terms (Program::terms,
  // children of the sum) at x as gradient_terms gives them: each blob's potential, 0 outside
  // its support.
  double gradient(const Program& p, const Vec3& x, Vec3* grad, int32_t* ids,
                  double* terms = nullptr) const;
  // The same from the blobs ids[0, n), in any order, instead of the point query: they must hold
  // every blob whose support holds x (a camera ray's list, BlobBeam). The ones whose supports
  // hold x are summed in increasing order, as the query's are: the same f and ∇f to the bit.
  // ids is overwritten.
  double gradient_among(const Program& p, const Vec3& x, int32_t* ids, int n, Vec3* grad,
                        double* terms = nullptr) const;
  // An upper bound of dot(n, x) over blob `id`'s support (its support function at n, |n| = 1,
  // through Outline below; +inf where none is known). A frustum's side plane with inward normal n
  // through the eye e holds none of the support where this is below dot(n, e).
  double support_extent(int id, const Vec3& n) const;
  // Whether blob `id` is no ball (terms() reads its frame; support_extent may know its outline).
  bool is_framed(int id) const { return !(blobs_[id].inv_r2 > 0); }
  // For a sum of at most kListed blobs, the order terms() takes them in (empty for more).
  const std::vector<int32_t>& listed() const { return listed_walk_; }
  int size() const { return static_cast<int>(blobs_.size()); }
  // Whether every blob is a ball (a cloud's): any four of them may go to ball_terms4.
  bool all_balls() const { return balls_ == size(); }
  // Whether blob `id` may add to the sum: its potential c2 r^2 + c3 r^3 is positive for some r in
  // (0, 1]. One that never does (a negative strength: c2, c3 <= 0) only subtracts, so it can
  // remove surface but never make any, and its terms' peaks are 0 (Term::peak).
  bool adds(int id) const { return blobs_[id].c2 > 0 || blobs_[id].c3 > 0; }
  // Whether some blob only subtracts (!adds).
  bool subtracts() const { return adders_ < size(); }
  // The most terms one stretch can have: one per ellipsoid, three per capsule.
  int max_terms() const { return size() + 2 * capsules_; }
  // The median of the blobs' mean support radii: how long a stretch meets a few of them.
  double typical_radius() const { return typical_radius_; }
  // Up to this many blobs are listed rather than searched: a walk of the BVH (its stack, a slab
  // test of every box) cost more than the blobs' own support tests (pov:molecule, 3 blobs: the
  // walk was 17 % of the frame's instructions).
  static constexpr int kListed = 16;

  // Where a blob's support is |q| <= 1 for q = L x + k less its nearest point of the segment from
  // 0 to `axis` (1 / |axis|^2 in inv_axis2; both 0 for an ellipsoid).
  struct Frame {
    Mat3 L;
    Vec3 k;
    Vec3 axis;
    double inv_axis2 = 0;
    // Whether L's entries off its diagonal are all zero (a segment's or an ellipsoid's frame
    // that no rotation or matrix placed: q = (X - a) / radius, X / radii). L x and L^T w then
    // take the diagonal's three products, where the rows' dot products took nine and six sums
    // (pov:chain's 24 capsules at 640x480: a camera or shadow ray's terms and a hit's gradient
    // take L x for every capsule they meet). The same values: each row's dot product adds to
    // its diagonal product those by the zeros, which are zeros (x is finite), so at most the
    // sign of a zero result differs.
    bool diagonal = false;
    Vec3 diagonal_times(const Vec3& x) const {
      return {L.r[0].x * x.x, L.r[1].y * x.y, L.r[2].z * x.z};
    }
    Vec3 times(const Vec3& x) const { return diagonal ? diagonal_times(x) : L * x; }
    Vec3 transposed_times(const Vec3& w) const {
      return diagonal ? Vec3{L.r[0].x * w.x, L.r[1].y * w.y, L.r[2].z * w.z}
                      : L.transposed_times(w);
    }
    // q at x: L x + k less its nearest point of the axis; the blob's r = 1 - |q|^2.
    Vec3 q(const Vec3& x) const {
      const Vec3 w = times(x) + k;
      if (!(inv_axis2 > 0)) return w;
      return w - axis * std::clamp(dot(w, axis) * inv_axis2, 0.0, 1.0);
    }
  };
  // What terms() reads first, in half a Frame's memory: the potential, and for a ball
  // (translations only, equal radii) its centre and 1 / radius^2, with which a ray's nearest
  // point to it costs a third of what L's does.
  // For any other blob, a sphere (centre, reach2 its radius squared) holding its support: a listed
  // blob (kListed) that a stretch passes farther from is skipped before its frame is read.
  struct Blob {
    Vec3 centre;
    double inv_r2;  // 0 where the blob is no ball
    double c2, c3;
    double reach2 = std::numeric_limits<double>::infinity();
    double axis2 = 0;  // |axis|^2 of its frame (0 for an ellipsoid): capsule_terms' scale
  };
  // A blob that is no ball, in world space: its support lies within `slack` of the points
  // p0 + s (p1 - p0) + M y, s in [0, 1], |y| <= 1, with M = L^-1 and p0, p1 the axis's ends
  // (p0 = p1 for an ellipsoid). `slack` bounds what the rounding of M, p0 and p1 moved, from their
  // residuals (blob_ray.cpp, set_outline); known is false where L is too ill-conditioned.
  struct Outline {
    Mat3 M;
    Vec3 p0, p1;
    double slack = 0;
    bool known = false;
  };
  // Four balls' terms of the stretch at once: lane i is the term terms_of_one gives the ball
  // ids[i] (each must be a ball: !is_framed), to the bit, in out[i] where bit i of the result is
  // set. With AVX2 where the CPU has it (chosen once, in of()), else ball_term lane by lane.
  unsigned ball_terms4(const int32_t (&ids)[4], const Vec3& o, const Vec3& d, double dd, double len,
                       Term (&out)[4]) const {
    const Blob* const lanes[4] = {&blobs_[ids[0]], &blobs_[ids[1]], &blobs_[ids[2]],
                                  &blobs_[ids[3]]};
    return lanes_(lanes, o, d, dd, len, out);
  }
  // ball_terms4's two kernels, which give the same bits (blob_ray_lanes.cpp: the same IEEE
  // operations in the same order in each lane, no fused multiply-add): the scalar one, and AVX2's,
  // only to be called where has_avx2().
  using BallLanes = unsigned (*)(const Blob* const (&balls)[4], const Vec3& o, const Vec3& d,
                                 double dd, double len, Term (&out)[4]);
  static unsigned ball_lanes_scalar(const Blob* const (&balls)[4], const Vec3& o, const Vec3& d,
                                    double dd, double len, Term (&out)[4]);
  static unsigned ball_lanes_avx2(const Blob* const (&balls)[4], const Vec3& o, const Vec3& d,
                                  double dd, double len, Term (&out)[4]);
  static bool has_avx2();

  // Each child's frame and potential, and the sum's group in the program (its BVH indexes the
  // children's support boxes): what a caller needs to sum the blobs itself (the mesher's leaves).
  const std::vector<Frame>& frames() const { return frames_; }
  const std::vector<Blob>& blobs() const { return blobs_; }
  int group() const { return group_; }

 private:
  std::vector<Frame> frames_;      // by child of the sum
  std::vector<Blob> blobs_;        // the same
  std::vector<Outline> outlines_;  // the same (not known for a ball)
  int group_ = 0;
  // For kListed blobs or fewer, the BVH's items (the blobs with a bounded, non-empty support) in
  // the order its segment query reports them, and in increasing order as its point query does:
  // the same terms in the same order, so the same sums to the bit. Empty for more blobs.
  std::vector<int32_t> listed_walk_, listed_sorted_;
  // A ball's term of the stretch (terms_of): its nearest point to the centre at mid, and how far
  // inside the support that is (h2 > 0); 0 terms where the stretch misses the support.
  static int ball_term(const Blob& b, const Vec3& o, const Vec3& d, double dd, double len,
                       Term* out) {
    const Vec3 oc = o - b.centre;
    const double mid = -dot(oc, d) / dd;
    const Vec3 nearest = oc + d * mid;
    const double h2 = 1 - dot(nearest, nearest) * b.inv_r2, alpha = dd * b.inv_r2;
    if (!(h2 > 0)) return 0;
    const double half = std::sqrt(h2 / alpha);
    const double enter = std::max(mid - half, 0.0), exit = std::min(mid + half, len);
    if (!(enter < exit)) return 0;
    const double gap = mid < enter ? enter - mid : mid > exit ? mid - exit : 0;
    const double r = std::max(h2 - alpha * gap * gap, 0.0);
    *out = {enter, exit, mid,  alpha,
            h2,    b.c2, b.c3, std::max(0.0, polynomial_potential(r, b.c2, b.c3))};
    return 1;
  }
  // The terms of blob `id`, which is no ball (terms_of's, from its frame: a capsule's up to three).
  int frame_terms(int32_t id, const Vec3& o, const Vec3& d, double len, Term* out) const;
  // gradient()'s sum over ids[0, found), in that order (increasing).
  double sum_gradient(const Program& p, const Vec3& x, const int32_t* ids, int found, Vec3* grad,
                      double* terms) const;
  BallLanes lanes_ = ball_lanes_scalar;  // ball_terms4's kernel for this CPU
  int capsules_ = 0;                     // frames with an axis
  int balls_ = 0;                        // blobs that are balls (inv_r2 > 0)
  int adders_ = 0;                       // blobs that may add (adds)
  double typical_radius_ = 0;
};

// The sum of the potentials of terms[active[i]], i < n, minus iso over [s0, s0 + S], as a
// polynomial in x = (u - s0) / S on [0, 1], with a bound on the rounding of its coefficients, of
// their Bernstein form and of its halvings (first_rise's err).
struct StretchPolynomial {
  double a[kMaxDegree + 1];
  int degree;
  double err;
};
StretchPolynomial stretch_polynomial(const BlobSum::Term* terms, const int* active, int n,
                                     double s0, double S, double iso);

// An upper bound of the sum of the potentials of terms[active[i]], i < n, over [u0, u1] (a piece:
// inside every one's [enter, exit]), with room for its rounding. Each term's own largest value
// there, where Term::peak is its largest over its whole range: a piece is skipped once the terms
// that reach iso somewhere have fallen below it (a shadow ray leaving a blob), and a negative
// blob counts with its least depth over the piece, not as 0 (a dimple keeps the pieces around it
// from reaching iso).
// Inline: first_hit_blobs calls it for most pieces (blob1000 at 640x480: 486,000 calls), and the
// call saved and restored a dozen of that loop's registers around each.
inline double piece_peak(const BlobSum::Term* terms, const int* active, int n, double u0,
                         double u1) {
  double sum = 0, magnitude = 0;
  for (int i = 0; i < n; ++i) {
    const BlobSum::Term& t = terms[active[i]];
    // r = h2 - alpha (u - mid)^2 is concave: over the piece it is largest at the piece's point
    // nearest mid and least at the end farthest from it. P(r) = c2 r^2 + c3 r^3 rises with r on
    // [0, 1] where c2, c3 >= 0 and falls where both are <= 0; a mixed one keeps its peak.
    double value = t.peak;
    if (t.c2 >= 0 && t.c3 >= 0) {
      const double x = std::clamp(t.mid, u0, u1) - t.mid;
      value = polynomial_potential(std::max(t.h2 - t.alpha * x * x, 0.0), t.c2, t.c3);
    } else if (t.c2 <= 0 && t.c3 <= 0) {
      const double x = std::max(std::abs(u0 - t.mid), std::abs(u1 - t.mid));
      value = polynomial_potential(std::max(t.h2 - t.alpha * x * x, 0.0), t.c2, t.c3);
    }
    sum += value;
    magnitude += std::abs(t.c2) + std::abs(t.c3);
  }
  // r is rounded to a few ulps of 1 (h2 <= 1 and alpha (u - mid)^2 <= h2 inside the support, up
  // to rounding), which moves P by a few ulps of |c2| + |c3| (|dP/dr| <= 2 |c2| + 3 |c3| on
  // [0, 1]); the sum adds n ulps of that. 1e-12 of it is a thousandfold room, and n * 1e-15 the
  // peak test's own (first_hit_blobs).
  return sum + 1e-12 * magnitude + n * 1e-15;
}

}  // namespace softtrace

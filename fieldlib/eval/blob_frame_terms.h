// One framed blob's terms of a stretch of ray (BlobSum::Term, blob_ray.h): an ellipsoid's one,
// a capsule's up to three. In a header so that a caller taking blobs one at a time (the camera
// sweep, tracer_blobs.cpp) runs inline the very arithmetic BlobSum::terms_of does: the same
// operations in the same order, so the same bits, with no call between.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "eval/blob_ray.h"
#include "kernels/potentials.h"

namespace softtrace {
namespace blob_frame {

// Where |w + u v|^2 is least along the line: at u = mid, where r = 1 - |w + u v|^2 is h2 (the
// support's depth there), alpha = |v|^2. v = 0 (a capsule's middle part seen along its axis)
// makes it constant (mid = 0).
struct Nearest {
  double alpha, mid, h2;
};
inline Nearest nearest(const Vec3& w, const Vec3& v) {
  const double alpha = dot(v, v);
  const double mid = alpha > 0 ? -dot(w, v) / alpha : 0.0;
  const Vec3 w_mid = w + v * mid;
  return {alpha, mid, 1 - dot(w_mid, w_mid)};
}

// The term of d^2 = |w + u v|^2 (its nearest point `m`) over the part [lo, hi] of the stretch
// [0, len], if its support r = 1 - d^2 > 0 meets that part. Inlined: a capsule calls it up to
// three times a stretch, and the calls were 2 % of pov:chain's instructions at 640x480.
__attribute__((always_inline)) inline bool term(const Nearest& m, double lo, double hi, double len,
                                                const BlobSum::Blob& b, BlobSum::Term* out) {
  const double alpha = m.alpha, mid = m.mid, h2 = m.h2;
  if (!(h2 > 0)) return false;
  const double half = alpha > 0 ? std::sqrt(h2 / alpha) : std::numeric_limits<double>::infinity();
  const double enter = std::max({mid - half, lo, 0.0}), exit = std::min({mid + half, hi, len});
  if (!(enter < exit)) return false;
  const double gap = mid < enter ? enter - mid : mid > exit ? mid - exit : 0;
  const double r = std::max(h2 - alpha * gap * gap, 0.0);
  // The largest value over the stretch: at the largest r for a positive strength, at most 0 for a
  // negative one.
  *out = {enter, exit, mid,  alpha,
          h2,    b.c2, b.c3, std::max(0.0, polynomial_potential(r, b.c2, b.c3))};
  return true;
}

// A capsule's terms: along the ray its point of the axis is s(u) = s0 + u sv times the axis,
// clamped to [0, 1]. Where s(u) <= 0, d^2 = |w + u v|^2 (the near end); where s(u) >= 1,
// d^2 = |w - axis + u v|^2 (the far end); between, the parts of w and v across the axis. The
// parts meet where s(u) is 0 and 1, and d^2 is continuous with its derivative there (the parts
// differ by |axis|^2 s^2), so rounding in those two points moves the sum by its square.
// Inlined in terms_of and in BlobSum::frame_terms: out of line, its call cost pov:blob1a 1.2 M
// instructions at 320x240.
[[gnu::always_inline]] inline int capsule_terms(const BlobSum::Frame& f, const BlobSum::Blob& b,
                                                const Vec3& w, const Vec3& v, double len,
                                                BlobSum::Term* out) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double s0 = dot(w, f.axis) * f.inv_axis2, sv = dot(v, f.axis) * f.inv_axis2;
  const Vec3 w_across = w - f.axis * s0, v_across = v - f.axis * sv;
  // The line's nearest point to the capsule's axis: where it passes clear of the cylinder around
  // the axis, it passes clear of the end balls inside it, and no part has a term (most rays miss
  // most long capsules). As computed: each end ball's |w_e + u v| is at least the cylinder's
  // |w_across + u v_across| less the rounding of s0, sv and the across parts (a few ulps of |w|,
  // |w_e| and |u v| <= |w_e| + 1 where an end term exists), and each h2 errs by a few ulps of
  // |w|^2 or |w_e|^2 <= 2 (|w|^2 + |axis|^2); so an end term's h2 > 0 leaves the cylinder's above
  // -1e-12 (1 + |w|^2 + |axis|^2), a thousandfold room. Below that, term() would find none.
  const Nearest across = nearest(w_across, v_across);
  const double scale = 1 + dot(w, w) + b.axis2;
  if (across.h2 < -1e-12 * scale) return 0;
  // [lo, hi] of each part: the near end's, the middle's, the far end's.
  double lo[3], hi[3];
  if (sv == 0) {  // the ray runs across the axis: one part all along
    const int part = s0 <= 0 ? 0 : s0 >= 1 ? 2 : 1;
    for (int i = 0; i < 3; ++i) {
      lo[i] = i == part ? -kInf : kInf;
      hi[i] = -lo[i];
    }
  } else {
    const double at0 = -s0 / sv, at1 = (1 - s0) / sv;  // where s is 0 and where it is 1
    if (sv > 0) {
      lo[0] = -kInf, hi[0] = at0, lo[1] = at0, hi[1] = at1, lo[2] = at1, hi[2] = kInf;
    } else {
      lo[2] = -kInf, hi[2] = at1, lo[1] = at1, hi[1] = at0, lo[0] = at0, hi[0] = kInf;
    }
  }
  // Whether an end part may have a term: its share of the stretch is not empty (term() needs
  // that), and the cylinder's r comes within rounding of 0 on it. An end ball's d^2 is the
  // cylinder's plus |axis|^2 times the square of s(u) beyond the end, so its support on the line
  // lies within the cylinder's; r, concave, is largest at the share's point nearest its mid. As
  // computed, r there errs by a few ulps of its parts (h2's of |w|^2 and |axis|^2 as above,
  // alpha (x - mid)^2's of itself): 1e-12 of those is the same thousandfold room. Most rays that
  // meet a capsule cross its middle only (pov:chain: 2 of every 3 end parts on the stretch
  // had no term, blob1a 24 of every 25 end parts), and skip the end balls' nearest points.
  const auto may_reach = [&](int i) {
    const double a = std::max(lo[i], 0.0), z = std::min(hi[i], len);
    if (!(a < z)) return false;
    const double x = std::clamp(across.mid, a, z) - across.mid, fall = across.alpha * x * x;
    return across.h2 - fall >= -1e-12 * (scale + fall);
  };
  int n = 0;
  if (may_reach(0)) n += term(nearest(w, v), lo[0], hi[0], len, b, out + n);
  n += term(across, lo[1], hi[1], len, b, out + n);
  if (may_reach(2)) n += term(nearest(w - f.axis, v), lo[2], hi[2], len, b, out + n);
  return n;
}

// BlobSum::frame_terms, inline in terms_of (a call per frame there added 2.4 M instructions to
// pov:blob1a's 380 M at 320x240).
[[gnu::always_inline]] inline int frame_terms_of(const BlobSum::Frame& f, const BlobSum::Blob& b,
                                                 const Vec3& o, const Vec3& d, double len,
                                                 BlobSum::Term* out) {
  // One test of Frame::diagonal for both products: times() twice tested it twice (pov:sheared,
  // whose frames are not diagonal, +0.9 M instructions at 320x240).
  Vec3 w, v;
  if (f.diagonal) {
    w = f.diagonal_times(o) + f.k, v = f.diagonal_times(d);
  } else {
    w = f.L * o + f.k, v = f.L * d;
  }
  if (f.inv_axis2 > 0) return capsule_terms(f, b, w, v, len, out);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  return term(nearest(w, v), -kInf, kInf, len, b, out);
}

// BlobSum::terms_of_one with a capsule's or ellipsoid's terms inline: the same arithmetic as its
// call of BlobSum::frame_terms, so the same bits (tests: FramedTermsOneAtATimeAreTheListsToTheBit).
// That call cost the camera sweep (tracer_blobs.cpp) the spills of its live registers around it
// and the callee's own frame, some 40 instructions a framed blob; pov:chain at 320x240 made
// 61,333 of them.
[[gnu::always_inline]] inline int terms_of_one(const BlobSum& sum, int32_t id, const Vec3& o,
                                               const Vec3& d, double dd, double len,
                                               BlobSum::Term* out) {
  if (!sum.is_framed(id)) return sum.terms_of_one(id, o, d, dd, len, out);  // a ball's, inline
  return frame_terms_of(sum.frames()[id], sum.blobs()[id], o, d, len, out);
}

}  // namespace blob_frame
}  // namespace softtrace

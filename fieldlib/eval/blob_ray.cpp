#include "eval/blob_ray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <vector>

#include "eval/blob_frame_terms.h"
#include "kernels/lp_metric.h"
#include "kernels/potentials.h"
#include "kernels/skeletal.h"
#include "math/affine.h"
#include "program/ops/gauge_ops.h"
#include "program/ops/placement_ops.h"
#include "program/ops/potential_ops.h"
#include "program/ops/skeletal_ops.h"

namespace softtrace {

namespace {
// What each op is to the pattern of a sum of polynomial blobs (BlobSum::of; docs/math.md §8):
// a placement of the point, the one oracle an affinely placed blob compiles to, a blob's
// distance, a potential of it (the kernels' potential_in_r says which are polynomials in
// r = 1 - d^2), its strength, or no part of a blob.
enum class BlobRole { Translate, Place, Oracle, Segment, LpMetric, Potential, Strength, None };
struct BlobPart {
  BlobRole role;
  PotentialType potential = PotentialType::Blanc;  // BlobRole::Potential: which
};

// One case per op of the op list (no default: -Werror=switch fails the build until a new op says
// what it is here). A child with an op of no part, or of a part out of place, is no blob: its sum
// keeps the general tracer (read_blob returns false, BlobSum::of nullopt).
BlobPart blob_part(Op op) {
  switch (op) {
    case Op::Translate:
      return {BlobRole::Translate};
    case Op::Place:
      return {BlobRole::Place};
    case Op::Oracle:
      return {BlobRole::Oracle};
    case Op::LineSegment:
      return {BlobRole::Segment};
    case Op::LpMetric:  // with n = 2: an ellipsoid (read_blob checks n)
      return {BlobRole::LpMetric};
    case Op::Blanc:
      return {BlobRole::Potential, PotentialType::Blanc};
    case Op::Wyvill:
      return {BlobRole::Potential, PotentialType::Wyvill};
    case Op::Murakami:
      return {BlobRole::Potential, PotentialType::Murakami};
    case Op::Cubic:
      return {BlobRole::Potential, PotentialType::Cubic};
    case Op::Strength:
      return {BlobRole::Strength};
    // Distances with no polynomial blob form, the other ops over a slot, and the n-ary ops (a
    // blob is a leaf of the one sum).
    case Op::SphericalProduct:
    case Op::ParallelPlanes:
    case Op::OneBranchPlane:
    case Op::Torus:
    case Op::GenDistance:
    case Op::PolarPrism:
    case Op::Offset:
    case Op::Complement:
    case Op::RadiusTransform:
    case Op::Group:
    case Op::Sum:
    case Op::Min:
    case Op::Max:
    case Op::SuperUnion:
    case Op::SuperIntersect:
    case Op::Perlin:
    case Op::Ricci:
    case Op::Scale:
    case Op::Bt:
      return {BlobRole::None};
  }
  std::abort();  // not reached: the switch names every op, and -Werror=switch keeps it so
}

// A capsule's axis in its frame (0 for an ellipsoid): its square and reciprocal must neither
// overflow nor vanish (the kernel divides by |ab|^2 in world units, and so loses nothing there).
bool set_axis(BlobSum::Frame* frame, const Vec3& axis) {
  const double a2 = dot(axis, axis);
  frame->axis = axis;
  frame->inv_axis2 = a2 > 0 ? 1 / a2 : 0.0;
  return a2 == 0 || (a2 > 1e-200 && a2 < 1e200);
}

// One child of the sum: placements from register 0, an ellipsoidal lp_metric or a segment of the
// last one, a polynomial potential of that, and optionally its strength s (which scales c2 and
// c3). The frame x -> M x + k is the placements' composition.
// An affinely placed blob (scale, matrix) compiles to one oracle instruction; its node says
// which blob it is. Its frame's rows must neither overflow nor vanish when squared (as below).
bool read_oracle_blob(const Instr& in, BlobSum::Frame* frame, BlobSum::Blob* blob) {
  PolynomialBlob b;
  if (!in.node->polynomial_blob(&b) || (b.c2 == 0 && b.c3 == 0)) return false;
  for (int r = 0; r < 3; ++r) {
    const Vec3& row = b.L.r[r];
    const double most = std::max({std::abs(row.x), std::abs(row.y), std::abs(row.z)});
    if (!(most > 1e-100 && most < 1e100 && std::abs(b.k[r]) < 1e100)) return false;
  }
  frame->L = b.L;
  frame->k = b.k;
  if (!set_axis(frame, b.axis)) return false;
  blob->centre = {};
  blob->inv_r2 = 0;  // no ball: terms() takes the frame
  blob->c2 = b.c2;
  blob->c3 = b.c3;
  return true;
}

// The blob's distance instruction `metric`: its frame's radii and origin (q = (X - a) / radius for
// a segment from a, X / radii for an ellipsoid) and its axis into *frame; false for a distance
// the pattern does not read.
bool read_distance(const Instr& metric, const double* K, BlobSum::Frame* frame, Vec3* radii,
                   Vec3* origin) {
  switch (blob_part(metric.op).role) {
    case BlobRole::Segment: {
      const LineSegmentParams m = LineSegmentOp::load(K + metric.a);
      *radii = {m.r, m.r, m.r};
      *origin = m.a;
      return set_axis(frame, m.len2 > 0 ? m.ab / m.r : Vec3{});
    }
    case BlobRole::LpMetric: {
      const LpMetricParams m = LpMetricOp::load(K + metric.a);
      if (m.n != 2) return false;
      *radii = m.a;
      *origin = {};
      set_axis(frame, {});
      return true;
    }
    case BlobRole::Translate:
    case BlobRole::Place:
    case BlobRole::Oracle:
    case BlobRole::Potential:
    case BlobRole::Strength:
    case BlobRole::None:
      return false;
  }
  std::abort();  // not reached: the switch names every role
}

// A blob frame's inverse M = L^-1 with the squares of the Frobenius norms of L and M: what the
// reach and the outline below both start from. False where L is ill-conditioned
// (|L|_F |L^-1|_F >= 1e8), where neither is kept.
struct FrameInverse {
  Mat3 M;
  double l2 = 0, m2 = 0;
};
bool frame_inverse(const BlobSum::Frame& f, FrameInverse* fi) {
  fi->M = inverse(f.L);
  for (int r = 0; r < 3; ++r) {
    fi->l2 += dot(f.L.r[r], f.L.r[r]);
    fi->m2 += dot(fi->M.r[r], fi->M.r[r]);
  }
  return fi->l2 * fi->m2 < 1e16;
}

// A sphere around a blob's support |L x + k - s axis| <= 1, s in [0, 1]: x = L^-1 (y + s axis - k)
// with |y| <= 1 lies within |L^-1|_2 (1 + |axis| / 2) of L^-1 (axis / 2 - k). |M|_2^2 is the
// largest eigenvalue of M^T M, at most its largest Gershgorin row sum, and at most |M|_F^2: the
// first is exact for a rotated ball or capsule (M^T M = radius^2 I), where the Frobenius norm is
// sqrt 3 too large (pov:chain's capsules' spheres had 1.7 times their radius). 1 % on the radius
// holds the inverse's rounding and M^T M's where L is well conditioned (frame_inverse); otherwise
// reach2 stays infinite (no sphere).
void set_reach(const BlobSum::Frame& f, const FrameInverse& fi, BlobSum::Blob* blob) {
  blob->centre = fi.M * (f.axis * 0.5 - f.k);
  double gershgorin = 0;
  for (int r = 0; r < 3; ++r) {
    double row = 0;
    for (int c = 0; c < 3; ++c) {
      double mtm = 0;  // (M^T M)_rc: columns r and c of M
      for (int i = 0; i < 3; ++i) mtm += fi.M.r[i][r] * fi.M.r[i][c];
      row += std::abs(mtm);
    }
    gershgorin = std::max(gershgorin, row);
  }
  const double norm2 = std::min(gershgorin, fi.m2);
  const double reach = 1.01 * std::sqrt(norm2) * (1 + 0.5 * std::sqrt(dot(f.axis, f.axis)));
  blob->reach2 = reach * reach;
}

// The outline of a blob that is no ball (BlobSum::Outline): with the computed M, p0 and p1 and
// the exact residuals r0 = L p0 + k, r1 = L p1 + k - axis and R = L M - I, a point x of the
// support (L x + k - s axis = y, |y| <= 1) is x = p(s) + L^-1 y' with p(s) = p0 + s (p1 - p0)
// and y' = y - (1 - s) r0 - s r1, so |y' - y| <= e = max |r_i|. Its point p(s) + M y of the
// outline is then within |L^-1 - M| (1 + e) + |M| e of it, and L^-1 - M = -M R (I + R)^-1 has
// norm at most |M| rho / (1 - rho) for rho >= |R| < 1 (all norms Frobenius, above the spectral
// ones). The computed residuals err by at most 4 ulps of the magnitudes summed in them (a dot of
// three and one addition); e and rho take 8 ulps of those besides, and the slack is doubled for
// its own rounding. An outline is kept only where L is well conditioned (frame_inverse) and
// rho < 1/2.
void set_outline(const BlobSum::Frame& f, const FrameInverse& fi, BlobSum::Outline* out) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const Mat3& M = fi.M;
  const double l_norm = std::sqrt(fi.l2), m_norm = std::sqrt(fi.m2);
  const Vec3 p0 = M * (-f.k), p1 = M * (f.axis - f.k);
  const Vec3 r0 = f.L * p0 + f.k, r1 = f.L * p1 + f.k - f.axis;
  const double k_norm = length(f.k), axis_norm = length(f.axis);
  const double e = 1.01 * std::max(length(r0), length(r1)) +
                   8 * kEps * (l_norm * std::max(length(p0), length(p1)) + k_norm + axis_norm);
  const Mat3 LM = times(f.L, M);
  double residual2 = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double entry = LM.r[r][c] - (r == c ? 1.0 : 0.0);
      residual2 += entry * entry;
    }
  const double rho = 1.01 * std::sqrt(residual2) + 8 * kEps * (l_norm * m_norm + 1);
  if (!(rho < 0.5) || !std::isfinite(e)) return;
  out->M = M;
  out->p0 = p0;
  out->p1 = p1;
  out->slack = 2 * m_norm * (rho / (1 - rho) * (1 + e) + e);
  out->known = true;
}

bool read_blob(const Program& p, const Group::Child& c, int32_t reg0, BlobSum::Frame* frame,
               BlobSum::Blob* blob) {
  if (c.end - c.begin == 1 && blob_part(p.code[c.begin].op).role == BlobRole::Oracle) {
    const Instr& in = p.code[c.begin];
    return in.in == reg0 && in.out == c.slot && read_oracle_blob(in, frame, blob);
  }
  Mat3 M;
  bool rotated = false;
  Vec3 off;
  int32_t reg = reg0;
  int32_t i = c.begin;
  const double* K = p.consts.data();
  for (; i < c.end; ++i) {
    const Instr& in = p.code[i];
    const BlobRole role = blob_part(in.op).role;
    if (role != BlobRole::Translate && role != BlobRole::Place) break;
    if (in.in != reg) return false;
    const Vec3 t = TranslateOp::load(K + in.a);  // Place's shift is laid out as Translate's
    off = off - t;
    if (role == BlobRole::Place) {  // local = Rt (x - t)
      rotated = true;
      const Mat3 Rt = PlaceOp::load_rotation(K + in.a);
      Mat3 next;
      for (int r = 0; r < 3; ++r)
        next.r[r] = M.r[0] * Rt.r[r].x + M.r[1] * Rt.r[r].y + M.r[2] * Rt.r[r].z;
      M = next;
      off = Rt * off;
    }
    reg = in.out;
  }
  if (c.end - i != 2 && c.end - i != 3) return false;
  const Instr& metric = p.code[i];
  const Instr& potential = p.code[i + 1];
  if (metric.in != reg || potential.in != metric.out) return false;
  Vec3 radii, origin;
  if (!read_distance(metric, K, frame, &radii, &origin)) return false;
  const BlobPart pot = blob_part(potential.op);
  if (pot.role != BlobRole::Potential || !potential_in_r(pot.potential, &blob->c2, &blob->c3))
    return false;
  if (c.end - i == 3) {
    const Instr& strength = p.code[i + 2];
    if (blob_part(strength.op).role != BlobRole::Strength || strength.in != potential.out ||
        strength.out != c.slot)
      return false;
    blob->c2 *= StrengthOp::load(K + strength.a);
    blob->c3 *= StrengthOp::load(K + strength.a);
  } else if (potential.out != c.slot) {
    return false;
  }
  off = off - origin;
  for (int r = 0; r < 3; ++r) {
    const double a = radii[r];
    // The squares of |L x + k| must neither overflow nor vanish for any point a ray reaches (the
    // kernel rescales those; these sums would lose the blob): such radii keep the segment tracer.
    if (!(a > 1e-100 && a < 1e100 && std::abs(off[r]) < 1e100)) return false;
    frame->L.r[r] = M.r[r] / a;
    frame->k[r] = off[r] / a;
  }
  const double a = radii.x;
  const bool ball_like = !rotated && a == radii.y && a == radii.z && frame->inv_axis2 == 0;
  blob->centre = -off;
  blob->inv_r2 = ball_like ? 1 / (a * a) : 0.0;
  return true;
}
}  // namespace

std::optional<BlobSum> BlobSum::of(const Program& p) {
  if (p.code.empty() || p.code.front().op != Op::Group) return std::nullopt;
  const Instr& sum = p.code.back();
  if (sum.op != Op::Sum || sum.out != p.result) return std::nullopt;
  const int32_t g = p.code.front().a;
  const Group& group = p.groups[g];
  if (group.op_index + 1 != static_cast<int32_t>(p.code.size()) || group.reg != 0 ||
      !group.always.empty() || group.children.empty())
    return std::nullopt;
  BlobSum s;
  s.group_ = g;
  s.lanes_ = has_avx2() ? ball_lanes_avx2 : ball_lanes_scalar;
  // Each child's parts in place: grown by doubling, a 1000-blob sum's vectors were copied ten
  // times over.
  s.frames_.reserve(group.children.size());
  s.blobs_.reserve(group.children.size());
  s.outlines_.reserve(group.children.size());
  int32_t next = 1;  // the children's code must tile the program between the Group and the Sum
  for (const Group::Child& c : group.children) {
    if (c.begin != next) return std::nullopt;
    Frame frame;
    Blob blob;
    if (!read_blob(p, c, group.reg, &frame, &blob)) return std::nullopt;
    frame.diagonal = frame.L.r[0].y == 0 && frame.L.r[0].z == 0 && frame.L.r[1].x == 0 &&
                     frame.L.r[1].z == 0 && frame.L.r[2].x == 0 && frame.L.r[2].y == 0;
    Outline outline;
    FrameInverse fi;
    if (!(blob.inv_r2 > 0) && frame_inverse(frame, &fi)) {
      set_reach(frame, fi, &blob);
      set_outline(frame, fi, &outline);
    }
    blob.axis2 = dot(frame.axis, frame.axis);
    s.capsules_ += frame.inv_axis2 > 0;
    s.balls_ += blob.inv_r2 > 0;
    s.frames_.push_back(frame);
    s.blobs_.push_back(blob);
    s.adders_ += s.adds(s.size() - 1);
    s.outlines_.push_back(outline);
    next = c.end;
  }
  if (next != group.op_index) return std::nullopt;
  if (s.size() <= kListed) {
    s.listed_walk_ = group.bvh.tree_order();
    s.listed_sorted_ = s.listed_walk_;
    std::sort(s.listed_sorted_.begin(), s.listed_sorted_.end());
  }
  // sqrt(3 / |L|_F^2) = sqrt(3 / Σ 1/a_i^2) for radii a_i, rotations aside: a mean of the radii
  // (a ball's radius for a ball).
  std::vector<double> radii;
  radii.reserve(s.frames_.size());
  for (const Frame& f : s.frames_)
    radii.push_back(std::sqrt(
        3 / (dot(f.L.r[0], f.L.r[0]) + dot(f.L.r[1], f.L.r[1]) + dot(f.L.r[2], f.L.r[2]))));
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  s.typical_radius_ = radii[radii.size() / 2];
  return s;
}

namespace {
// Does the stretch o + u d, u in [0, len], pass within a listed blob's sphere (Blob::reach2)? d is
// a unit vector to rounding, so -oc.d is the nearest point's u to a few ulps of |oc|, which moves
// its distance by their square; the distance is rounded to a few ulps of |oc|^2 + len^2: 1e-12
// of that is room.
bool within_reach(const BlobSum::Blob& b, const Vec3& o, const Vec3& d, double len) {
  const Vec3 oc = o - b.centre;
  const Vec3 nearest = oc + d * std::clamp(-dot(oc, d), 0.0, len);
  return dot(nearest, nearest) <= b.reach2 + 1e-12 * (dot(oc, oc) + len * len);
}
}  // namespace

double BlobSum::support_extent(int id, const Vec3& n) const {
  const Outline& o = outlines_[id];
  if (!o.known) return std::numeric_limits<double>::infinity();
  return std::max(dot(n, o.p0), dot(n, o.p1)) + length(o.M.transposed_times(n)) + o.slack;
}

int BlobSum::terms(const Program& p, const Vec3& o, const Vec3& d, double len, double pad,
                   Term* out, int32_t* ids) const {
  int found = 0;
  if (size() <= kListed) {
    // A listed ball takes its own support test below (h2 > 0, enter < exit), as cheap as a box
    // test; any other blob first its sphere's. Either keeps every blob the BVH's query would.
    // Balls alone are all kept: the list itself, not copied (pov:molecule's and pov:blob's
    // shadow rays, three balls each: 88 instructions a ray besides terms_of).
    if (all_balls())
      return terms_of(listed_walk_.data(), static_cast<int>(listed_walk_.size()), o, d, len, out);
    for (const int32_t id : listed_walk_)
      if (blobs_[id].inv_r2 > 0 || within_reach(blobs_[id], o, d, len)) ids[found++] = id;
  } else {
    found = p.groups[group_].bvh.segment_items(o, o + d * len, pad, ids);
  }
  return terms_of(ids, found, o, d, len, out);
}

int BlobSum::cone_items(const Program& p, const Vec3& apex, const Vec3 (&normals)[4], double pad,
                        int32_t* out) const {
  if (size() <= kListed) {
    std::copy(listed_walk_.begin(), listed_walk_.end(), out);
    return static_cast<int>(listed_walk_.size());
  }
  return p.groups[group_].bvh.cone_items(apex, normals, pad, out);
}

int BlobSum::cone_items(const Program& p, const Vec3& apex, const Vec3 (&normals)[4],
                        const double (&pads)[4], int32_t* out) const {
  if (size() <= kListed) {
    std::copy(listed_walk_.begin(), listed_walk_.end(), out);
    return static_cast<int>(listed_walk_.size());
  }
  return p.groups[group_].bvh.cone_items(apex, normals, pads, out);
}

int BlobSum::frame_terms(int32_t id, const Vec3& o, const Vec3& d, double len, Term* out) const {
  return blob_frame::frame_terms_of(frames_[id], blobs_[id], o, d, len, out);
}

int BlobSum::terms_of(const int32_t* ids, int found, const Vec3& o, const Vec3& d, double len,
                      Term* out) const {
  const double dd = dot(d, d);
  int n = 0;
  for (int i = 0; i < found; ++i) {
    const Blob& b = blobs_[ids[i]];
    if (b.inv_r2 > 0) {
      // A run of balls four at a time (a shadow ray's list is mostly balls in a cloud), their
      // terms kept in the list's order: the same terms as one at a time, to the bit. With the
      // AVX2 kernel a run of three (pov:molecule's whole list, every ray) takes it too, its fourth
      // lane given the third ball again and that term dropped: one kernel's work where each
      // ball's was a call of ball_term. Not a run of two: there the kernel cost more than the two
      // calls (pov:golfball, pov:blob1b).
      const bool three =
          i + 3 <= found && blobs_[ids[i + 1]].inv_r2 > 0 && blobs_[ids[i + 2]].inv_r2 > 0;
      const bool four = three && i + 4 <= found && blobs_[ids[i + 3]].inv_r2 > 0;
      if (four || (three && lanes_ != ball_lanes_scalar)) {
        const int run = four ? 4 : 3;
        Term lanes[4];
        const unsigned has =
            ball_terms4({ids[i], ids[i + 1], ids[i + 2], ids[i + run - 1]}, o, d, dd, len, lanes);
        for (int k = 0; k < run; ++k)
          if (has >> k & 1) out[n++] = lanes[k];
        i += run - 1;
        continue;
      }
      n += ball_term(b, o, d, dd, len, out + n);
      continue;
    }
    // No sphere test first (within_reach): it skipped few of the blobs a list or a query gives.
    // A camera or shadow beam keeps a capsule or ellipsoid only where its outline meets the
    // beam's pyramid (support_extent); a ray without a list takes the BVH's segment query of the
    // supports' boxes. On pov:chain at 320x240 it skipped 20,293 of 142,638 frames, for 53
    // instructions each, and a frame's own tests give those no term (their supports hold none of
    // the stretch), so the terms are the same. Callgrind, whole process, 1 thread, 320x240,
    // without it: pov:chain -0.8 %, cloud300 -1.9 %, pov:golfball -0.3 %, cloud3000 -0.3 %.
    n += blob_frame::frame_terms_of(frames_[ids[i]], b, o, d, len, out + n);
  }
  return n;
}

double BlobSum::gradient(const Program& p, const Vec3& x, Vec3* grad, int32_t* ids,
                         double* terms) const {
  const Group& sum = p.groups[group_];
  // As in terms(): a listed blob that does not hold x fails r > 0.
  const int32_t* found_ids = listed_sorted_.data();
  int found = static_cast<int>(listed_sorted_.size());
  if (size() > kListed) {
    found = sum.kept_at(x, ids);
    found_ids = ids;
  }
  return sum_gradient(p, x, found_ids, found, grad, terms);
}

namespace {
// A blob's w at x, as sum_gradient and gradient_among both take it (one function, so that the
// two sums see the same bits): a ball's L is diagonal (1 / radius, read_blob), so L x + k and
// L^T q go without the products by L's zeros, which add only zeros (the same values; at most a
// zero's sign differs, where a product by L's diagonal is itself zero). `l` is the ball's 1 /
// radius.
[[gnu::always_inline]] inline Vec3 w_at(const BlobSum::Frame& frame, bool ball, const Vec3& x,
                                        double l) {
  return ball ? Vec3{l * x.x + frame.k.x, l * x.y + frame.k.y, l * x.z + frame.k.z} : frame.q(x);
}
}  // namespace

double BlobSum::gradient_among(const Program& p, const Vec3& x, int32_t* ids, int n, Vec3* grad,
                               double* terms) const {
  // One pass over the list takes each blob's w and r by sum_gradient's very arithmetic and keeps
  // the blobs with r > 0 -- exactly the ones sum_gradient would sum, as the point query gives them
  // -- with their potential and gradient, computed once; these are then summed in increasing id
  // order, as the query's are. (The list was filtered by a looser test, sorted, and each kept
  // blob's q taken again in sum_gradient: a fifth of a cloud's normals.) Few blobs hold a point
  // (1 to 5 in a dense cloud, a few more on pov:chain's capsules); past kKept of them the ids
  // kept are sorted and summed by sum_gradient, the same values.
  constexpr int kKept = 32;
  // Plain doubles, not a Vec3: the arrays are left uninitialised (Vec3's zeros were 32 stores a
  // call). A kept blob stays in its slot; its key, id * 256 + slot, is what is sorted. Each
  // quantity in an array of its own: in one record (term, gx, gy, gz), GCC stored a kept blob's
  // values in pairs and the sum read (gx, gy) as one load across two of those stores, which
  // waited for both to reach the cache (perf, meets10 at 640x480: this function 4.6 % of the
  // frame's samples, a fifth of them after that load; apart, 3.7 %). Reordered in the record,
  // GCC still read a pair across two stores.
  double kept_term[kKept];
  double kept_gx[kKept], kept_gy[kKept], kept_gz[kKept];  // dP/dr times ∇r = -2 L^T q
  uint64_t keys[kKept];
  int found = 0;
  for (int i = 0; i < n; ++i) {
    const int32_t id = ids[i];
    const Blob& b = blobs_[id];
    const Frame& frame = frames_[id];
    const bool ball = b.inv_r2 > 0;
    const double l = frame.L.r[0].x;
    const Vec3 w = w_at(frame, ball, x, l);
    const double r = 1 - dot(w, w);
    if (!(r > 0)) continue;
    ids[found] = id;
    if (found < kKept) {
      const double slope = -2 * polynomial_potential_slope(r, b.c2, b.c3);
      const Vec3 gradient = (ball ? w * l : frame.transposed_times(w)) * slope;
      kept_term[found] = polynomial_potential(r, b.c2, b.c3);
      kept_gx[found] = gradient.x;
      kept_gy[found] = gradient.y;
      kept_gz[found] = gradient.z;
      keys[found] = uint64_t(uint32_t(id)) << 8 | uint64_t(found);
    }
    ++found;
  }
  if (found > kKept) {
    std::sort(ids, ids + found);
    return sum_gradient(p, x, ids, found, grad, terms);
  }
  // An insertion sort of the keys in place (ids are distinct, so the keys sort by id): a
  // fraction of std::sort's call for so few, and one word moved where a Kept was five.
  for (int i = 1; i < found; ++i) {
    const uint64_t k = keys[i];
    int j = i;
    for (; j > 0 && keys[j - 1] > k; --j) keys[j] = keys[j - 1];
    keys[j] = k;
  }
  const Group& sum = p.groups[group_];
  const bool reports = terms && !sum.terms.empty();
  if (terms) std::fill(terms, terms + p.terms, 0.0);
  double f = 0;
  Vec3 g;
  for (int i = 0; i < found; ++i) {
    const size_t k = keys[i] & 0xff;
    f += kept_term[k];
    if (reports) {
      const int32_t id = int32_t(keys[i] >> 8);
      if (sum.terms[id] >= 0) terms[sum.terms[id]] = kept_term[k];
    }
    g += Vec3{kept_gx[k], kept_gy[k], kept_gz[k]};
  }
  *grad = g;
  return f;
}

double BlobSum::sum_gradient(const Program& p, const Vec3& x, const int32_t* found_ids, int found,
                             Vec3* grad, double* terms) const {
  const Group& sum = p.groups[group_];
  const bool reports = terms && !sum.terms.empty();
  if (terms) std::fill(terms, terms + p.terms, 0.0);
  double f = 0;
  Vec3 g;
  for (int i = 0; i < found; ++i) {
    const Frame& frame = frames_[found_ids[i]];
    const Blob& b = blobs_[found_ids[i]];
    const bool ball = b.inv_r2 > 0;
    const double l = frame.L.r[0].x;
    const Vec3 w = w_at(frame, ball, x, l);
    const double r = 1 - dot(w, w);
    if (!(r > 0)) continue;
    const double term = polynomial_potential(r, b.c2, b.c3);
    f += term;
    if (reports && sum.terms[found_ids[i]] >= 0) terms[sum.terms[found_ids[i]]] = term;
    // dP/dr times ∇r = -2 L^T q.
    const double slope = -2 * polynomial_potential_slope(r, b.c2, b.c3);
    g += (ball ? w * l : frame.transposed_times(w)) * slope;
  }
  *grad = g;
  return f;
}

StretchPolynomial stretch_polynomial(const BlobSum::Term* terms, const int* active, int n,
                                     double s0, double S, double iso) {
  StretchPolynomial sp{};
  sp.degree = 4;
  double magnitude = iso;  // Σ of the terms' absolute coefficients' values at x = 1
  for (int i = 0; i < n; ++i) {
    const BlobSum::Term& t = terms[active[i]];
    // r(s0 + S x) = R0 + R1 x + R2 x^2.
    const double delta = s0 - t.mid;
    const double R0 = t.h2 - t.alpha * delta * delta, R1 = -2 * t.alpha * delta * S,
                 R2 = -t.alpha * S * S;
    const double r2[5] = {R0 * R0, 2 * R0 * R1, R1 * R1 + 2 * R0 * R2, 2 * R1 * R2, R2 * R2};
    for (int j = 0; j < 5; ++j) sp.a[j] += t.c2 * r2[j];
    const double m = std::abs(R0) + std::abs(R1) + std::abs(R2);
    magnitude += m * m * (std::abs(t.c2) + std::abs(t.c3) * m);
    if (t.c3 == 0) continue;
    sp.degree = 6;
    for (int j = 0; j < 5; ++j) {
      sp.a[j] += t.c3 * r2[j] * R0;
      sp.a[j + 1] += t.c3 * r2[j] * R1;
      sp.a[j + 2] += t.c3 * r2[j] * R2;
    }
  }
  sp.a[0] -= iso;
  // Each coefficient is a sum of products of the R's, each term bounded by the magnitude; Horner,
  // the Bernstein conversion and some 60 halvings each add a few ulps of it. 128 + n ulps hold
  // all of that with room.
  sp.err = (128 + n) * std::numeric_limits<double>::epsilon() * magnitude;
  return sp;
}

}  // namespace softtrace

#include "eval/blob_ray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kernels/lp_metric.h"

namespace softtrace {

namespace {
// P(r) = c2 r^2 + c3 r^3 for r = 1 - d^2 in [0, 1]: Murakami's (1 - d^2)^2, and Wyvill's
// 1 - 22/9 d^2 + 17/9 d^4 - 4/9 d^6, whose constant and linear terms in r cancel.
bool potential_in_r(Op op, double* c2, double* c3) {
  if (op == Op::Murakami) {
    *c2 = 1;
    *c3 = 0;
    return true;
  }
  if (op == Op::Cubic) {  // r^3
    *c2 = 0;
    *c3 = 1;
    return true;
  }
  if (op == Op::Wyvill) {
    *c2 = 5.0 / 9;
    *c3 = 4.0 / 9;
    return true;
  }
  return false;
}

// One child of the sum: placements from register 0, an ellipsoidal lp_metric of the last one,
// a polynomial potential of that, and optionally its strength s (which scales c2 and c3). The
// frame x -> M x + k is the placements' composition.
bool read_blob(const Program& p, const Group::Child& c, int32_t reg0, BlobSum::Frame* frame,
               BlobSum::Blob* blob) {
  Mat3 M;
  bool rotated = false;
  Vec3 off;
  int32_t reg = reg0;
  int32_t i = c.begin;
  const double* K = p.consts.data();
  for (; i < c.end && (p.code[i].op == Op::Translate || p.code[i].op == Op::Place); ++i) {
    const Instr& in = p.code[i];
    if (in.in != reg) return false;
    const Vec3 t{K[in.a], K[in.a + 1], K[in.a + 2]};
    off = off - t;
    if (in.op == Op::Place) {  // local = Rt (x - t), Rt row-major after t
      rotated = true;
      Mat3 Rt;
      for (int r = 0; r < 3; ++r)
        Rt.r[r] = {K[in.a + 3 + 3 * r], K[in.a + 4 + 3 * r], K[in.a + 5 + 3 * r]};
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
  if (metric.op != Op::LpMetric || metric.in != reg) return false;
  const LpMetricParams m = LpMetricParams::load(K + metric.a);
  if (m.n != 2) return false;
  if (potential.in != metric.out) return false;
  if (!potential_in_r(potential.op, &blob->c2, &blob->c3)) return false;
  if (c.end - i == 3) {
    const Instr& strength = p.code[i + 2];
    if (strength.op != Op::Strength || strength.in != potential.out || strength.out != c.slot)
      return false;
    blob->c2 *= K[strength.a];
    blob->c3 *= K[strength.a];
  } else if (potential.out != c.slot) {
    return false;
  }
  for (int r = 0; r < 3; ++r) {
    const double a = m.a[r];
    // The squares of |L x + k| must neither overflow nor vanish for any point a ray reaches (the
    // kernel rescales those; these sums would lose the blob): such radii keep the segment tracer.
    if (!(a > 1e-100 && a < 1e100 && std::abs(off[r]) < 1e100)) return false;
    frame->L.r[r] = M.r[r] / a;
    frame->k[r] = off[r] / a;
  }
  const double a = m.a.x;
  const bool ball_like = !rotated && a == m.a.y && a == m.a.z;
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
  int32_t next = 1;  // the children's code must tile the program between the Group and the Sum
  for (const Group::Child& c : group.children) {
    if (c.begin != next) return std::nullopt;
    Frame frame;
    Blob blob;
    if (!read_blob(p, c, group.reg, &frame, &blob)) return std::nullopt;
    s.frames_.push_back(frame);
    s.blobs_.push_back(blob);
    next = c.end;
  }
  if (next != group.op_index) return std::nullopt;
  // sqrt(3 / |L|_F^2) = sqrt(3 / Σ 1/a_i^2) for radii a_i, rotations aside: a mean of the radii
  // (a ball's radius for a ball).
  std::vector<double> radii;
  for (const Frame& f : s.frames_)
    radii.push_back(std::sqrt(
        3 / (dot(f.L.r[0], f.L.r[0]) + dot(f.L.r[1], f.L.r[1]) + dot(f.L.r[2], f.L.r[2]))));
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  s.typical_radius_ = radii[radii.size() / 2];
  return s;
}

int BlobSum::terms(const Program& p, const Vec3& o, const Vec3& d, double len, double pad,
                   Term* out, int32_t* ids) const {
  const Vec3 e = o + d * len;
  const int found = p.groups[group_].bvh.segment_items(o, e, pad, ids);
  const double dd = dot(d, d);
  int n = 0;
  for (int i = 0; i < found; ++i) {
    // The nearest point to the centre at mid, and how far inside the support it is (h2 > 0).
    double alpha, mid, h2;
    const Blob& b = blobs_[ids[i]];
    if (b.inv_r2 > 0) {
      const Vec3 oc = o - b.centre;
      mid = -dot(oc, d) / dd;
      const Vec3 nearest = oc + d * mid;
      h2 = 1 - dot(nearest, nearest) * b.inv_r2;
      alpha = dd * b.inv_r2;
    } else {
      const Frame& f = frames_[ids[i]];
      const Vec3 w = f.L * o + f.k, v = f.L * d;
      alpha = dot(v, v);
      mid = -dot(w, v) / alpha;
      const Vec3 w_mid = w + v * mid;
      h2 = 1 - dot(w_mid, w_mid);
    }
    if (!(h2 > 0 && alpha > 0)) continue;
    const double half = std::sqrt(h2 / alpha);
    const double enter = std::max(mid - half, 0.0), exit = std::min(mid + half, len);
    if (!(enter < exit)) continue;
    const double gap = mid < enter ? enter - mid : mid > exit ? mid - exit : 0;
    const double r = std::max(h2 - alpha * gap * gap, 0.0);
    // The largest value over the stretch: at the largest r for a positive strength, at most 0
    // for a negative one.
    out[n++] = {enter, exit, mid, alpha, h2, b.c2, b.c3, std::max(0.0, r * r * (b.c2 + b.c3 * r))};
  }
  return n;
}

double BlobSum::gradient(const Program& p, const Vec3& x, Vec3* grad, int32_t* ids) const {
  const int found = p.groups[group_].kept_at(x, ids);
  double f = 0;
  Vec3 g;
  for (int i = 0; i < found; ++i) {
    const Frame& frame = frames_[ids[i]];
    const Blob& b = blobs_[ids[i]];
    const Vec3 w = frame.L * x + frame.k;
    const double r = 1 - dot(w, w);
    if (!(r > 0)) continue;
    f += r * r * (b.c2 + b.c3 * r);
    // dP/dr times ∇r = -2 L^T w.
    g += frame.L.transposed_times(w) * (-2 * r * (2 * b.c2 + 3 * b.c3 * r));
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

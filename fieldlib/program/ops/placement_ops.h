// The placements: a point register moved into a child's frame, by a translation (Translate) or a
// rotation after it (Place). Constants: t[3], then for Place Rt[9] row-major (local = Rt (x - t)).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "math/box.h"
#include "math/vec.h"
#include "program/ops/op_io.h"

namespace softtrace {

// Register in.out's segment from that of in.in: the same affine map as the points.
inline void place_segment(const Instr& in, const BoundsIO& io, bool rotate) {
  const double* t = io.K + in.a;
  const Vec3 shift{t[0], t[1], t[2]};
  const Vec3* S = io.segs + 2 * in.in;
  Vec3* O = io.segs + 2 * in.out;
  double pad = io.seg_pads[in.in] +
               kSegmentRounding * (max_abs(shift) + std::max(max_abs(S[0]), max_abs(S[1])));
  for (int e = 0; e < 2; ++e) O[e] = S[e] - shift;
  if (rotate) {
    const double* M = t + 3;
    double norm = 0;  // the largest row sum of |Rt|: how far it can move a point
    for (int e = 0; e < 2; ++e) {
      const Vec3 v = O[e];
      for (int i = 0; i < 3; ++i)
        O[e][i] = M[3 * i] * v.x + M[3 * i + 1] * v.y + M[3 * i + 2] * v.z;
    }
    for (int i = 0; i < 3; ++i)
      norm = std::max(norm, std::abs(M[3 * i]) + std::abs(M[3 * i + 1]) + std::abs(M[3 * i + 2]));
    pad = pad * norm * (1 + kSegmentRounding) +
          kSegmentRounding * std::max(max_abs(O[0]), max_abs(O[1]));
  }
  io.seg_pads[in.out] = pad;
}

// Register out = register in - t.
struct TranslateOp : RegisterToRegister {
  static constexpr bool kZeroWhenQuiet = false;
  // An array, not a vector: every translated child of a cloud is compiled with one.
  static std::array<double, 3> constants(const Vec3& t) { return {t.x, t.y, t.z}; }
  static Vec3 load(const double* c) { return {c[0], c[1], c[2]}; }

  static void values(const Instr& in, const LaneIO& io) {
    const double* t = io.K + in.a;
    for (int i = 0; i < 3; ++i) {
      const double* src = io.reg(in.in, i);
      double* dst = io.reg(in.out, i);
      for (int l = 0; l < io.n; ++l) dst[l] = src[l] - t[i];
    }
  }
  static void value(const Instr& in, const PointIO& io) {
    const double* t = io.K + in.a;
    const Vec3& q = io.R[in.in];
    io.R[in.out] = {q.x - t[0], q.y - t[1], q.z - t[2]};
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const double* t = io.K + in.a;
    const LocalFrame& f = io.R[in.in];
    io.R[in.out] = {{f.p.x - t[0], f.p.y - t[1], f.p.z - t[2]}, f.J, f.identity};
  }
  // fl(x - t) is monotone in x, so [fl(lo - t), fl(hi - t)] holds every computed local point; one
  // ulp more (<= 2^-52 |v|, plus 1e-300 for subnormals) holds the exact ones.
  static void bounds(const Instr& in, const BoundsIO& io) {
    if (io.segment) {
      place_segment(in, io, false);
      return;
    }
    const Box& b = io.boxes[in.in];
    const double* t = io.K + in.a;
    Box o;
    for (int i = 0; i < 3; ++i) {
      o.lo[i] = widen_down(b.lo[i] - t[i], kEps);
      o.hi[i] = widen_up(b.hi[i] - t[i], kEps);
    }
    io.boxes[in.out] = o;
  }
};

// Register out = Rt (register in - t).
struct PlaceOp : RegisterToRegister {
  static constexpr bool kZeroWhenQuiet = false;
  static std::vector<double> constants(const Vec3& t, const Mat3& Rt) {
    return {t.x,       t.y,       t.z,       Rt.r[0].x, Rt.r[0].y, Rt.r[0].z,
            Rt.r[1].x, Rt.r[1].y, Rt.r[1].z, Rt.r[2].x, Rt.r[2].y, Rt.r[2].z};
  }
  static Vec3 load_shift(const double* c) { return {c[0], c[1], c[2]}; }
  static Mat3 load_rotation(const double* c) {
    Mat3 Rt;
    for (int i = 0; i < 3; ++i) Rt.r[i] = {c[3 + 3 * i], c[4 + 3 * i], c[5 + 3 * i]};
    return Rt;
  }

  static void values(const Instr& in, const LaneIO& io) {
    const double* t = io.K + in.a;
    const double* M = t + 3;
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double *qx = io.reg(in.out, 0), *qy = io.reg(in.out, 1), *qz = io.reg(in.out, 2);
    for (int l = 0; l < io.n; ++l) {
      const double u = px[l] - t[0], v = py[l] - t[1], w = pz[l] - t[2];
      qx[l] = M[0] * u + M[1] * v + M[2] * w;
      qy[l] = M[3] * u + M[4] * v + M[5] * w;
      qz[l] = M[6] * u + M[7] * v + M[8] * w;
    }
  }
  static void value(const Instr& in, const PointIO& io) {
    const double* t = io.K + in.a;
    const double* M = t + 3;
    const Vec3& q = io.R[in.in];
    const double u = q.x - t[0], v = q.y - t[1], w = q.z - t[2];
    io.R[in.out] = {M[0] * u + M[1] * v + M[2] * w, M[3] * u + M[4] * v + M[5] * w,
                    M[6] * u + M[7] * v + M[8] * w};
  }
  static void gradient(const Instr& in, const GradIO& io) {
    const double* t = io.K + in.a;
    const Mat3 Rt = load_rotation(t);
    const LocalFrame& f = io.R[in.in];
    io.R[in.out] = {Rt * (f.p - Vec3{t[0], t[1], t[2]}), f.identity ? Rt : times(Rt, f.J), false};
  }
  // The box around Rt (b - t): centre through Rt, half extent through |Rt|, padded by 1e-12 of
  // the magnitudes (the few products and sums err by far less).
  static void bounds(const Instr& in, const BoundsIO& io) {
    if (io.segment) {
      place_segment(in, io, true);
      return;
    }
    const Box& b = io.boxes[in.in];
    if (!b.bounded()) {
      io.boxes[in.out] = Box::unbounded();
      return;
    }
    const double* t = io.K + in.a;
    const double* M = t + 3;
    const Vec3 c = b.center() - Vec3{t[0], t[1], t[2]}, h = b.extent() * 0.5;
    Box o;
    for (int i = 0; i < 3; ++i) {
      const double ci = M[3 * i] * c.x + M[3 * i + 1] * c.y + M[3 * i + 2] * c.z;
      const double hi =
          std::abs(M[3 * i]) * h.x + std::abs(M[3 * i + 1]) * h.y + std::abs(M[3 * i + 2]) * h.z;
      const double pad = 1e-12 * (std::abs(ci) + hi) + kTiny;
      o.lo[i] = ci - hi - pad;
      o.hi[i] = ci + hi + pad;
    }
    io.boxes[in.out] = o;
  }

 private:
  static Mat3 times(const Mat3& A, const Mat3& B) {
    Mat3 C;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        C.r[i][j] = A.r[i][0] * B.r[0][j] + A.r[i][1] * B.r[1][j] + A.r[i][2] * B.r[2][j];
    return C;
  }
};

}  // namespace softtrace

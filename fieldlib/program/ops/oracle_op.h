// An oracle: a model node evaluates its whole subtree at a point register (program/oracle.h), with
// its own outward-rounded bounds.
#pragma once

#include "program/ops/op_io.h"

namespace softtrace {

struct OracleOp : RegisterToSlot {
  static constexpr bool kZeroWhenQuiet = false;

  // Its virtual call per lane, only for its own subtree.
  static void values(const Instr& in, const LaneIO& io) {
    const double *px = io.reg(in.in, 0), *py = io.reg(in.in, 1), *pz = io.reg(in.in, 2);
    double* out = io.slot(in.out);
    for (int l = 0; l < io.n; ++l) out[l] = in.node->eval({px[l], py[l], pz[l]}, nullptr);
  }
  static void value(const Instr& in, const PointIO& io) {
    io.S[in.out] = in.node->eval(io.R[in.in], nullptr);
  }
  static void gradient(const Instr& in, const GradIO& io) {
    io.local(in, [&](const Vec3& q, Vec3* g) { return in.node->eval(q, g); });
  }
  static void bounds(const Instr& in, const BoundsIO& io) {
    const NodeBounds nb = in.node->box_bounds(io.box(in.in));
    io.I[in.out] = nb.value;
    io.L[in.out] = nb.lipschitz;
    io.D[in.out] = {-io.L[in.out], io.L[in.out]};
    io.Q[in.out] = 0;
  }
};

}  // namespace softtrace

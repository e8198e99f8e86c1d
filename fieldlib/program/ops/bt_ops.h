// BT_k of 003 without bulge elimination, with its children's code before it (docs/math.md §7; the
// kernel kernels/bt_blend.h): an instruction of its own, not an oracle, so that along a segment
// its slope comes from its children's (docs/math.md §8, "Slopes along a segment"). Bulge
// elimination stays an oracle: its ranges and weights follow the children's gradients.
#pragma once

#include "kernels/bt_blend.h"
#include "math/scratch.h"
#include "program/ops/nary_ops.h"

namespace softtrace {

// Constants (at in): BtCombination's.
struct BtOp : Combination<BtOp> {
  static void values(const Instr& in, const LaneIO& io) {
    const BtCombination bt = BtCombination::load(io.K + in.in);
    double* out = io.slot(in.out);
    Slots<double> f(in.n);
    for (int l = 0; l < io.n; ++l) {
      for (int j = 0; j < in.n; ++j) f.set(j, io.S[io.args[in.a + j] * kBatch + l]);
      out[l] = bt.value(f.data(), nullptr);
    }
  }
  static double combine(const Instr& in, const double* K, const double* f) {
    return BtCombination::load(K + in.in).value(f, nullptr);
  }
  static double combine(const Instr& in, const double* K, const double* f, Vec3* g, Vec3* grad) {
    Slots<double> df(in.n);
    const double v = BtCombination::load(K + in.in).value(f, df.data());
    Vec3 s;
    for (int j = 0; j < in.n; ++j) s += g[j] * df[j];
    *grad = s;
    return v;
  }
  // The node's box bounds (model/blends_bt.cpp, the same function) and, on a segment, the hull of
  // the active children's τσ_i f_i'/m_i, capped by the Lipschitz bound.
  static void bounds(const Instr& out, const BoundsIO& io) {
    double lipschitz;
    Interval slope;
    const BtCombination bt = BtCombination::load(io.K + out.in);
    io.I[out.out] =
        bt.bounds([&](int j) { return io.I[io.child(j).slot]; },
                  [&](int j) { return io.L[io.child(j).slot]; },
                  [&](int j) { return io.D[io.child(j).slot]; }, io.segment, &lipschitz, &slope);
    io.L[out.out] = lipschitz;
    io.Q[out.out] = 0;
    io.D[out.out] =
        io.segment ? BoundsIO::capped(slope, lipschitz) : Interval{-lipschitz, lipschitz};
  }
};

}  // namespace softtrace

// A BT_k blend without bulge elimination as the program stores it (program/ops/bt_ops.h) and the
// node answers the box question with it (model/blends_bt.cpp): R = τ·BT_k(σ_1 f_1, ..., σ_k f_k)
// on the conic or hyper-ellipsoidal base (bt_base.h, docs/math.md §7), its value, its monotone
// enclosure, its Lipschitz bound and its slope along a segment from the children's.
//
// Slope along a segment (docs/math.md §8, "Slopes along a segment"): with w_i = m_i ∂_iBT, which
// are >= 0 ([BT-5]) and sum to 1 ([BT-2]), BT' = Σ_i ∂_iBT x_i' = Σ_i w_i (x_i'/m_i), a convex
// combination of the x_i'/m_i over the children that can be active (w_i = 0 for the others): so
// R' = τ BT' lies in the hull of τσ_i [f_i']/m_i over those children. BT is C^1 off the kinks of
// min outside the blending region, where it is some x_j/m_j, so difference quotients lie in the
// same hull.
#pragma once

#include <vector>

#include "math/interval.h"

namespace softtrace {

// Constants (at in): conic (1 or 0), τ, k, then σ[k], r[k], p[k], m[k] (the conic: r = {r1, r2},
// p = {p, 0}).
struct BtCombination {
  bool conic;
  int tau, k;
  const double *sigma, *r, *p, *m;

  static std::vector<double> constants(bool conic, int tau, const std::vector<int>& sigma,
                                       const std::vector<double>& r, const std::vector<double>& p,
                                       const std::vector<double>& m);
  static BtCombination load(const double* c) {
    const int k = static_cast<int>(c[2]);
    return {c[0] != 0, static_cast<int>(c[1]), k, c + 3, c + 3 + k, c + 3 + 2 * k, c + 3 + 3 * k};
  }

  // BT(x) of the operands x_i = σ_i f_i (not τ's sign), ∂_iBT into dx (nullable).
  double base(const double* x, double* dx) const;
  // R from the children's values f (k of them), ∂R/∂f_i = τσ_i ∂_iBT into df (nullable).
  double value(const double* f, double* df) const;
  // From the children's intervals I, Lipschitz bounds L and (nullable) slopes D along a segment:
  // R's interval (BT at the operands' ends, padded by the root finder's tolerance), the largest
  // L_i/m_i over the children that can be active into *lipschitz, and R's slope into *slope
  // (uncapped; untouched when D is null).
  Interval bounds(const Interval* I, const double* L, const Interval* D, double* lipschitz,
                  Interval* slope) const;
};

}  // namespace softtrace

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

#include <algorithm>
#include <vector>

#include "kernels/bt_base.h"
#include "math/interval.h"
#include "math/scratch.h"

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
  // From child i's interval I(i), Lipschitz bound L(i) and, where `slopes`, slope D(i) along a
  // segment: R's interval (BT at the operands' ends, padded by the root finder's tolerance), the
  // largest L_i/m_i over the children that can be active into *lipschitz, and R's slope into
  // *slope (uncapped; untouched unless `slopes`). Inline, over accessors: the Bt instruction
  // reads its children's slots in place, on every bounds pass.
  template <class FI, class FL, class FD>
  Interval bounds(const FI& I, const FL& L, const FD& D, bool slopes, double* lipschitz,
                  Interval* slope) const {
    Slots<double> lo(k), hi(k);  // the ends of X_i = σ_i [f_i]
    for (int i = 0; i < k; ++i) {
      const Interval f = I(i);
      lo.set(i, sigma[i] > 0 ? f.lo : -f.hi);
      hi.set(i, sigma[i] > 0 ? f.hi : -f.lo);
    }
    // BT is non-decreasing in every x_i ([BT-5]): its range is between its values at the ends,
    // each padded by twice the root finder's tolerance (the end's error and the sample's).
    const double vlo = base(lo.data(), nullptr), vhi = base(hi.data(), nullptr);
    const Interval bt = iv::out(vlo - 2 * bt_value_tolerance(lo.data(), k, vlo, r, m),
                                vhi + 2 * bt_value_tolerance(hi.data(), k, vhi, r, m));
    double Lr = 0;
    Interval s{0, 0};
    bool any = false;
    for (int i = 0; i < k; ++i) {
      if (!bt_can_be_active(i, k, lo.data(), hi.data(), r, m, m)) continue;
      Lr = std::max(Lr, iv::up(L(i) / m[i]));
      if (!slopes) continue;
      // τσ_i [f_i']/m_i, rounded outward
      const Interval d = tau * sigma[i] > 0 ? D(i) : -D(i);
      const Interval q = iv::out(d.lo / m[i], d.hi / m[i]);
      s = any ? hull(s, q) : q;
      any = true;
    }
    *lipschitz = Lr;
    if (slopes) *slope = s;
    return tau > 0 ? bt : -bt;
  }
};

}  // namespace softtrace

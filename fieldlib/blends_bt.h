// The BT_k blends of 003 (MATH.md §6.2, §7), zero convention only (inside f <= 0): the union
// BT_k(f_1..f_k), its duals (§7.4) intersection -BT_k(-f_1..-f_k) and difference
// -BT_k(-f_1, f_2..f_k), and the displacement union BD_k (all m_i = 1). Every node computes
// R = τ·BT(x) with x_i = σ_i f_i (τ, σ_i = ±1 per the duals). The scalar maths is in bt_base.h.
//
// Gradient (§7.5): ∇R = τ Σ_i ∂_iBT(x) σ_i ∇f_i, the partials from the implicit function theorem.
//
// Lipschitz, derived (MATH.md §8 "BT composition"): by [BT-5] and [BT-2] the weights
// w_i = m_i ∂_iBT are >= 0 and sum to 1, so
//   |∇R| <= Σ_i ∂_iBT |∇f_i| <= Σ_i w_i (L_i/m_i) <= max_i L_i/m_i,
// a convex combination of the L_i/m_i. R is continuous and C^1 off the measure-zero kinks of min
// outside the blending region, so the bound on |∇R| bounds its difference quotients too. Over a
// box the same holds with the children's box bounds L_i(B), and the max runs only over children
// that can be active: ∂_iBT = 0 wherever x_i - m_i·min_{j≠i} x_j/m_j >= r_i (the hyper-ellipsoid
// term i is [(r_i - x_i + m_i h)/r_i]_+ = 0 since h <= min_j x_j/m_j; for the conic, x is
// outside region II with arg-min j), so child i is dropped when that holds for the whole box,
// checked with its interval lower end and the others' upper ends.
//
// Interval over a box: BT is non-decreasing in every x_i ([BT-5]), so with X_i = σ_i·[f_i](B),
// BT(B) ⊂ [BT(X.lo), BT(X.hi)], evaluated with infinite endpoints where a child has no finite
// enclosure (bt_base.h); each end is padded by twice the solver tolerance
// (BtOperator::value_tolerance) to absorb the root finder's error at both the end and the sample.
//
// Region (a box containing {R <= c} or {R >= c}), from h_lo <= BT <= h_hi:
//   BT <= c' ⇒ some i has x_i <= r_i + m_i c'   (BT >= min_i (x_i - r_i)/m_i): union of boxes;
//   BT >= c' ⇒ every i has x_i >= m_i c'        (BT <= min_i x_i/m_i): intersection of boxes.
// So the union's {BT <= c} lies in ∪_i f_i.region(r_i + m_i c, Below); the intersection's
// {R <= c} (= {BT(-f) >= -c}) in ∩_i f_i.region(m_i c, Below) (R >= max_i f_i/m_i); the
// difference's {R <= c} in f_1.region(m_1 c, Below) ∩_{j>1} f_j.region(-m_j c, Above). Levels
// are rounded outward.
//
// Bulge elimination (003 §5, MATH.md §7.6; k = 2, `bulge_elimination: {omega}`): r_i and m_i
// become P_i(X) = r_i(1 - cosθ + ω) ∈ [r_i ω, r_i(2 + ω)] and M_i(X) >= m_i ([BE-3]), computed
// from the union operands' gradients g_i = σ_i ∇f_i (so a dual uses the angle between the
// gradients its union sees). A conic base then needs p < ω² r1 r2 so that p < P_1 P_2 at
// every X (checked at load time).
// - Gradient: MATH.md's implementation choice, the paper's partial gradient Σ ∂_iBT σ_i ∇f_i
//   with P and M frozen at X. The exact gradient adds ∂_rBT ∇P + ∂_mBT ∇M, which needs the
//   children's Hessians (through cosθ and G = |∇f_1|/|∇f_2|); nodes do not provide them.
// - Lipschitz: +inf, globally and over boxes. A sound bound on the full field needs bounds on
//   ∇P and ∇M, i.e. on the children's Hessians and a positive lower bound on |∇f_2| (M_1 grows
//   like G), which the node interface does not provide. The renderer then relies on intervals.
// - Interval: still available from the bracket, which holds pointwise for any positive r and m:
//   min_i (x_i - P_i)/M_i <= BT <= min_i x_i/M_i with P_i <= r_i(2 + ω) and M_i ∈ [m_i, ∞).
//   Per argument the worst cases are X_i.hi/m_i (or a value just below 0 when X_i.hi < 0) above,
//   and (X_i.lo - r_i(2+ω))/m_i (or a value just above 0 when that is positive) below: the
//   magnitude is lost where M_i is unbounded, but the sign is kept, which is what lets the
//   renderer skip space.
// - Region: {BT <= c'} with c' <= 0: x_i <= P_i + M_i c' <= r_i(2+ω) + m_i c'; {BT >= c'} with
//   c' >= 0: x_i >= M_i c' >= m_i c'. Other levels have no finite bound (M_i unbounded):
//   Box::unbounded().
#pragma once

#include "registry.h"

namespace softtrace {

// `base`: "conic" (k = 2; r1, r2 > 0, p < r1 r2) or "hyperellipsoid" (r_i > 0, p_i > 1 lists);
// `m` (each > 0, default 1); optional `bulge_elimination: {omega > 0}` (k = 2).
NodePtr create_bt_union(const Params& p, const BuildContext& ctx);            // 003 Eq. 2–5
NodePtr create_bt_intersection(const Params& p, const BuildContext& ctx);     // 003 §3.3
NodePtr create_bt_difference(const Params& p, const BuildContext& ctx);       // 003 §3.3
NodePtr create_displacement_union(const Params& p, const BuildContext& ctx);  // 003 §2.2

}  // namespace softtrace

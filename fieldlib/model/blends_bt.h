// The BT_k blends of 003 (docs/math.md §6.2, §7), zero convention only (inside f <= 0): the union
// BT_k(f_1..f_k), its duals (§7.4) intersection -BT_k(-f_1..-f_k) and difference
// -BT_k(-f_1, f_2..f_k), and the displacement union BD_k (all m_i = 1). Every node computes
// R = τ·BT(x) with x_i = σ_i f_i (τ, σ_i = ±1 per the duals). The scalar maths is in bt_base.h.
//
// Gradient (§7.5): ∇R = τ Σ_i ∂_iBT(x) σ_i ∇f_i, the partials from the implicit function theorem.
//
// Lipschitz, derived (docs/math.md §8 "BT composition"): by [BT-5] and [BT-2] the weights
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
// Bulge elimination (003 §5, docs/math.md §7.6; k = 2, `bulge_elimination: {omega}`): r_i and m_i
// become P_i(X) = r_i(1 - cosθ + ω) ∈ [r_i ω, r_i(2 + ω)] and M_i(X) >= m_i ([BE-3]), computed
// from the union operands' gradients g_i = σ_i ∇f_i (so a dual uses the angle between the
// gradients its union sees). A conic base then needs p < ω² r1 r2 so that p < P_1 P_2 at
// every X (checked at load time).
// - Gradient: the true one (docs/math.md §7.6), not the paper's partial Σ ∂_iBT g_i with P and M
//   frozen at X: ∇BT = Σ_i ∂_iBT ∇g_i + Σ_i (∂_{r_i}BT ∇P_i + ∂_{m_i}BT ∇M_i), ∂_{r_i}BT from
//   BtOperator::range_derivatives, ∂_{m_i}BT = -BT ∂_iBT, ∇P_i and ∇M_i from the operands'
//   Hessians through ∇cosθ and ∇G (kernels/bulge_gradient.h). A child's Hessian is its exact
//   FieldNode::hessian where the kind has one, else central differences of its gradient.
// - Lipschitz over a box B, derived; +inf globally, and wherever a child gives no gradient floor
//   or Hessian bound (node.h). With c = 1 - cosθ + ω, P_i = r_i c:
//     ∇BT = Σ_i ∂_iBT ∇x_i + ∂_cBT ∇c + Σ_i ∂_{M_i}BT ∇M_i.
//   (1) <= max_i L_i/m_i, as without bulges (the weights M_i ∂_iBT sum to 1, M_i >= m_i).
//   (2) The hyper-ellipsoid (and the conic with p = 0) is homogeneous in the ranges,
//       BT(x; c r, M) = c·φ(x/c) with φ = BT(·; r, M), so ∂_cBT = φ(y) - ∇φ(y)·y = -Σ_i ∂_iφ u_i
//       (y = x/c, u = y - Mφ(y) on the base surface, so 0 <= u_i <= r_i where ∂_iφ > 0), and
//       |∂_cBT| <= max_i r_i/M_i. |∇c| = |∇cosθ| <= |H_1|/|∇f_1| + |H_2|/|∇f_2| (the unit
//       normals n_i have |∇n_i| <= |H_i|/|∇f_i|). A conic p != 0 does not scale: +inf.
//   (3) ∂_{M_i}BT = -BT·∂_iBT, so |(3)| <= |BT| max_i |∇M_i|/m_i. By §7.6, where [cosθ]_+ > 0,
//       |∇M_1| <= (m_2 G_hi - m_1)_+ |∇cosθ| + m_2 |∇G| and |∇M_2| <= (m_1/G_lo - m_2)_+ |∇cosθ| +
//       m_1 |∇G|/G_lo², with G ∈ [G_lo, G_hi] = [floor_1/L_2, L_1/floor_2] and
//       |∇G| <= |H_1|/floor_2 + L_1|H_2|/floor_2² (|∇|∇f_i|| <= |H_i|, 0 if floor_i = L_i).
//       The two cases of M_i agree where they meet ([BE-4]), so the bound holds across them.
//   The children bound |∇f_i| from below (gradient_floor) and their Hessians (hessian_bound)
//   over B, and |BT| comes from the interval below. cosθ's range over B is cosθ(centre) ±
//   |∇cosθ|·half-diagonal, which narrows P_i's range and, where cosθ <= 0 on all of B, pins
//   M = m (then (3) = 0). Children that cannot be active in B are left out of (1) and (2) (see
//   the box bound above), and (2) vanishes when only one can. Sampled looseness on 003 Fig. 9's
//   hub: 3x to 12x on average.
// - Interval over B: for a homogeneous base (as in (2)) BT is non-decreasing in x, non-increasing
//   in c, and monotone in each M_i with the sign of -BT, which M does not change ([BT-1]); so
//   BT(B) lies between min(BT(X.lo; P_hi, m), BT(X.lo; P_hi, M_hi)) and max(BT(X.hi; P_lo, m),
//   BT(X.hi; P_lo, M_hi)), padded like the plain enclosure. Otherwise the bracket, which holds
//   pointwise for any positive r and m: min_i (x_i - P_i)/M_i <= BT <= min_i x_i/M_i, whose worst
//   cases are X_i.hi/m_i (X_i.hi/M_hi when X_i.hi < 0) above and (X_i.lo - P_hi)/m_i (divided by
//   M_hi when positive) below; where M_hi is unbounded (no gradient floor) only the sign is
//   kept, which still lets the renderer skip space.
// - Region: {BT <= c'} with c' <= 0: x_i <= P_i + M_i c' <= r_i(2+ω) + m_i c'; {BT >= c'} with
//   c' >= 0: x_i >= M_i c' >= m_i c'. Other levels have no finite bound (M_i unbounded):
//   Box::unbounded().
#pragma once

#include "describe/build_context.h"
#include "model/node.h"

namespace softtrace {

// `base`: "conic" (k = 2; r1, r2 > 0, p < r1 r2) or "hyperellipsoid" (r_i > 0, p_i > 1 lists);
// `m` (each > 0, default 1); optional `bulge_elimination: {omega > 0}` (k = 2).
NodePtr create_bt_union(const Params& p, const BuildContext& ctx);            // 003 Eq. 2–5
NodePtr create_bt_intersection(const Params& p, const BuildContext& ctx);     // 003 §3.3
NodePtr create_bt_difference(const Params& p, const BuildContext& ctx);       // 003 §3.3
NodePtr create_displacement_union(const Params& p, const BuildContext& ctx);  // 003 §2.2

}  // namespace softtrace

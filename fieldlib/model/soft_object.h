// Soft objects f = P(T(d(X))) (docs/math.md §4; 000 Eq. 9, 002 Eq. 1), with the optional radius
// transform under "radii" (radius_transforms.h holds the formulas and their bounds).
// Bounds:
// - interval: P is non-increasing and T(d; w) monotone (radius_transforms.h), so the image is
//   P of T's image over [d] × [w]; for surface-defined radii [w] comes from [d]/[f] - 1 (T_a*,
//   contour with f = fc/2) or 1 - [d]/[f] (T_s*), clamped to [w_min, w_max].
// - Lipschitz over a box: |P'|([T]) · (sup|∂T/∂d| L_d + sup|dT/dw| sup|∇w|), where
//   |∇w| = |f∇d - d∇f|/f^2 <= L_d/f.lo + d.hi L_f/f.lo^2, or, near the skeleton where f.lo -> 0,
//   |∇w| <= r (L_d + r L_f)/d with r = sup d/f, paired with sup|dT/dw|/d. 0 where T is 0 or 1
//   over the whole box (P∘T constant), e.g. T_a* with d >= 0.5(1+w_min) and f >= 0.5 ([TA-1]),
//   T_s* with d < 0.5(1-w_min) and f < 0.5 ([TS-1]). [d]/[f] ignores that d and f are
//   correlated, so where [w] comes out wide both bounds are refined over up to two levels of
//   octants (each sub-box bound is sound; the smaller result is kept). The compiled program's
//   RadiusTransform instruction keeps the unrefined bounds (eval_bounds.cpp says why).
//   Global: the chain rule with constant w; +inf for surface-defined radii (w has no global
//   bound) and T_l with w1 > 1 ([TL-3]).
// - support: plain/T_n/T_l {d < 0.5(1+w1)}, T_r and T_s* {d < 1}, T_a* {f_a < 0.5} ∪
//   {d < 0.5(1+w_min)} ([TA-2]; the second set only matters where the w_min clamp acts),
//   contour {fc < 1} ∪ {d < 0.5(1+w_min)}.
#pragma once

#include "describe/build_context.h"
#include "model/node.h"
#include "model/potential.h"

namespace softtrace {

NodePtr create_soft_object(const Params& p, const BuildContext& ctx);

// Radius transforms (the "radii" of a soft object): P(T(d)) for the transform described by `r`.
NodePtr create_T_n(const Params& r, NodePtr d, PotentialPtr P,
                   const BuildContext& ctx);  // 002 Eq. 10
NodePtr create_T_l(const Params& r, NodePtr d, PotentialPtr P,
                   const BuildContext& ctx);  // 002 Eq. 13
NodePtr create_T_r(const Params& r, NodePtr d, PotentialPtr P,
                   const BuildContext& ctx);  // 002 Eq. 14
NodePtr create_T_an(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx);  // Eq. 11
NodePtr create_T_al(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx);  // Eq. 11
NodePtr create_T_sn(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx);  // Eq. 12
NodePtr create_T_sr(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx);  // Eq. 12
NodePtr create_contour(const Params& r, NodePtr d, PotentialPtr P,
                       const BuildContext& ctx);  // 000 Eqs. 14-15

}  // namespace softtrace

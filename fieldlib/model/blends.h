// Blends (docs/math.md §5, §6.3) and the complement. Children are built in the object's convention.
// Bounds, derived per operator (each .cpp repeats the argument next to the code):
// - soft_blend Σ f_i: interval Σ [f_i]; Lipschitz Σ L_i (triangle inequality); support ∪ supports.
// - perlin_*: products of g_i = f_i or 1 - f_i; interval arithmetic on the product (sound for any
//   range); |∇B| <= Σ_i sup|Π_{j≠i} g_j| L_i ([PE-3]); region from the factors that must be > 0
//   (union: ∪ supports, intersection: ∩ supports, difference: support of the first child).
// - ricci_*: power means (Σ g_i^q)^(1/q), q = ±n, of g_i = f_i, 1 - f_i or 1/f_i
//   (blends_ricci.cpp); monotone in every g_i, so the interval is B at the ends; for q = n >= 1
//   |∇B| <= (Σ (c_i L_i)^n)^(1/n) (Hölder, [RS-3]); for q = -n, ∂B/∂g_i = (B/g_i)^(n+1) sum to at
//   most 1, so |∇B| <= max_i c_i L_i; c_i = sup|g_i'|.
// - min/max: interval min/max of the intervals; Lipschitz max L_i.
// - scale_*: BSA2/BSS2 are degree-1 homogeneous with ∂B/∂x_i >= 0 (blends_scale.cpp), so
//   Euler's relation bounds Σ ∂B/∂x_i: <= 1 for BSA2 and <= 1/(1 - max r_i) for BSS2.
// - complement: 1 - f, -f, or 1/max(f, 1e-12) (constructive, guarded at f <= 0).
#pragma once

#include "describe/build_context.h"
#include "kernels/scale_operator.h"  // ScaleOperator, which the tests call directly
#include "model/node.h"

namespace softtrace {

NodePtr create_soft_blend(const Params& p, const BuildContext& ctx);  // 000 Eq. 12, 002 Eq. 3

NodePtr create_perlin_union(const Params& p, const BuildContext& ctx);         // 002 Eq. 4
NodePtr create_perlin_intersection(const Params& p, const BuildContext& ctx);  // 002 Eq. 5
NodePtr create_perlin_difference(const Params& p, const BuildContext& ctx);    // 002 Eq. 6
NodePtr create_min(const Params& p, const BuildContext& ctx);
NodePtr create_max(const Params& p, const BuildContext& ctx);
NodePtr create_complement(const Params& p, const BuildContext& ctx);  // docs/math.md §1

NodePtr create_ricci_union(const Params& p, const BuildContext& ctx);  // 000 Eq. 6, 002 Eq. 7
NodePtr create_ricci_intersection(const Params& p, const BuildContext& ctx);  // 002 Eq. 8
NodePtr create_ricci_difference(const Params& p, const BuildContext& ctx);  // docs/math.md A5, R21

NodePtr create_scale_union(const Params& p, const BuildContext& ctx);  // 000 Eq. 8, §6.3
NodePtr create_scale_intersection(const Params& p, const BuildContext& ctx);

// offset s·(f - c) (003 §2.1; kernels/offset.h): `children` (exactly one), `scale` s != 0
// (default 1), `level` c (default 1).
NodePtr create_offset(const Params& p, const BuildContext& ctx);

}  // namespace softtrace

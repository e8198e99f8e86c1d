// Distance functions (docs/math.md §2): ray-linear about a centre or skeleton, value 1 on the
// node's surface. Bounds, as derived in docs/math.md §8 and gauge.h:
// - interval: each is non-decreasing in the |coordinate|/radius terms, so the image of a box is
//   the function at the terms' lower and upper ends (segment: distance ± half-diagonal/radius).
// - Lipschitz, global: the l_q -> l_2 operator norm of the gauge's weights (gauge_lipschitz);
//   nested gauges compose it because the inner gradient is orthogonal to the outer axis.
//   Infinite for exponents below 1.
// - Lipschitz over a box: the chain rule with every partial (u_i/f)^(n-1) bounded from the
//   interval of u_i and f (power_sum_partial_bound), so it is finite on boxes away from the
//   singular planes even for exponents below 1.
// - region(c, Below): {d <= c} lies in the box of half-sides c·radius (a power sum is at least
//   its largest term, [DF-5]); with side lengths t the half-sides are c·t_{2i-1}·a and c·t_{2i}·a,
//   the cylinder's z range grows by ±L. Planes have no finite region.
// Each family file states the derivation of its own bounds above its classes.
#pragma once

#include "describe/build_context.h"
#include "model/node.h"

namespace softtrace {

NodePtr create_parallel_planes(const Params& p, const BuildContext& ctx);   // 000 Eq. 2, §2.3
NodePtr create_one_branch_plane(const Params& p, const BuildContext& ctx);  // 002 §4.5, §2.4
NodePtr create_lp_metric(const Params& p, const BuildContext& ctx);         // 000 Eq. 2, §2.5
NodePtr create_superquadric(const Params& p, const BuildContext& ctx);      // 000 Eq. 3, 002 Eq. 15
NodePtr create_generalized_distance(const Params& p,
                                    const BuildContext& ctx);      // 000 Eq. 4, 002 Eq. 16, §2.7
NodePtr create_segment(const Params& p, const BuildContext& ctx);  // 000 Eq. 5, §2.8
NodePtr create_superelliptic_cylinder(const Params& p,
                                      const BuildContext& ctx);  // 002 Eqs. 17-18, §2.9
NodePtr create_torus(const Params& p,
                     const BuildContext& ctx);  // circle skeleton (docs/scene-format.md)
NodePtr create_polar_prism(const Params& p, const BuildContext& ctx);  // §10.1 rose / star
NodePtr create_super_ellipsoidal_union(const Params& p,
                                       const BuildContext& ctx);  // 000 Eq. 6, §5.3, 002 §4.5
NodePtr create_super_ellipsoidal_intersection(const Params& p, const BuildContext& ctx);

}  // namespace softtrace

// Distance functions (MATH.md §2): ray-linear about a centre or skeleton, value 1 on the node's
// surface. Bounds, as derived in MATH.md §8 and gauge.h:
// - interval: each is non-decreasing in the |coordinate|/radius terms, so the image of a box is
//   the function at the terms' lower and upper ends (segment: distance ± half-diagonal/radius).
// - Lipschitz, global: the l_q -> l_2 operator norm of the gauge's weights (gauge_lipschitz);
//   nested gauges compose it because the inner gradient is orthogonal to the outer axis.
//   Infinite for exponents below 1.
// - Lipschitz over a box: the chain rule with every partial (u_i/f)^(n-1) bounded from the
//   interval of u_i and f (power_sum_partial_bound), so it is finite on boxes away from the
//   singular planes even for exponents below 1.
// - region(c, Below): {d <= c} lies in the box of half-sides c·radius (a power sum is at least
//   its largest term, [DF-5]).
#pragma once

#include "registry.h"

namespace softtrace {

NodePtr create_lp_metric(const Params& p, const BuildContext& ctx);     // 000 Eq. 2, §2.5
NodePtr create_superquadric(const Params& p, const BuildContext& ctx);  // 000 Eq. 3, §2.6
NodePtr create_segment(const Params& p, const BuildContext& ctx);       // 000 Eq. 5, §2.8

}  // namespace softtrace

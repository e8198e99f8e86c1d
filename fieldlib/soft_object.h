// Soft objects f = P(d(X)) (MATH.md §4.1; 000 Eq. 9, 002 Eq. 1).
// Bounds: interval P([d]) (P is monotone); Lipschitz |P'|([d]) · L_d by the chain rule, 0 where
// d >= 1 over the whole box; support {d < 1} ⊂ d.region(1, Below).
#pragma once

#include "registry.h"

namespace softtrace {

NodePtr create_soft_object(const Params& p, const BuildContext& ctx);

}  // namespace softtrace

// Blends without range parameters (MATH.md §5). Bounds: the sum's interval is the sum of the
// children's intervals and its Lipschitz bound the sum of theirs (triangle inequality); its
// support is the union of the children's supports (soft fields are >= 0).
#pragma once

#include "registry.h"

namespace softtrace {

NodePtr create_soft_blend(const Params& p, const BuildContext& ctx);  // 000 Eq. 12, 002 Eq. 3

}  // namespace softtrace

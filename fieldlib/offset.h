// offset: s·(f - c) (docs/scene-format.md "Blends"; 003 §2.1): turns a distance function d, whose
// surface is d = 1, into a zero-convention defining function, e.g. s = 1, c = 1 gives d - 1 (inside
// <= 0). Bounds, derived from the child's: interval s·([f] - c) by interval arithmetic; Lipschitz
// |s|·L (globally and per box); region: s(f - c) <= l ⇔ f <= c + l/s for s > 0 and f >= c + l/s for
// s < 0 (sides swap for >=), with the level c + l/s rounded outward.
#pragma once

#include "build_context.h"
#include "node.h"

namespace softtrace {

// `children` (exactly one), `scale` s != 0 (default 1), `level` c (default 1).
NodePtr create_offset(const Params& p, const BuildContext& ctx);

}  // namespace softtrace

// A soft object's "strength" (docs/scene-format.md "soft_object", docs/math.md §4.10): the node
// s·f around a soft object f, and the check that keeps negative strengths out of blends whose
// formulas need fields in [0, 1].
#pragma once

#include "describe/params.h"
#include "model/node.h"

namespace softtrace {

// s·child; s finite and non-zero. s = 1 returns the child itself (the same program bits).
NodePtr with_strength(NodePtr child, double s);

// Refuses, at the pointer of the first negative "strength" among the soft objects of p's
// "children" (searched through every nested node), a blend named `blend` whose formula needs its
// children in [0, 1] (Perlin's products, Ricci's powers, the scale method).
void refuse_negative_strength(const Params& p, const char* blend);

}  // namespace softtrace

// Helpers for node files that need a node's whole range.
#pragma once

#include <cmath>

#include "math/bound_util.h"
#include "model/node.h"

namespace softtrace {

// The node's range over all of space: its interval over the unbounded box, or the whole line
// when that is not informative (NaN from inf/inf in a child's interval arithmetic).
inline Interval global_range(const FieldNode& n) {
  const Interval r = n.interval(Box::unbounded());
  if (std::isnan(r.lo) || std::isnan(r.hi)) return Interval::entire();
  return r;
}

}  // namespace softtrace

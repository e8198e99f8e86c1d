// Small helpers shared by the blend nodes.
#pragma once

#include <algorithm>
#include <cmath>

#include "node.h"

namespace softtrace {

// sup |v| over an interval.
inline double magnitude(Interval a) {
  return std::max(std::abs(a.lo), std::abs(a.hi));
}

// The node's range over all of space: its interval over the unbounded box, or the whole line
// when that is not informative (NaN from inf/inf in a child's interval arithmetic).
inline Interval global_range(const FieldNode& n) {
  const Interval r = n.interval(Box::unbounded());
  if (std::isnan(r.lo) || std::isnan(r.hi)) return Interval::entire();
  return r;
}

}  // namespace softtrace

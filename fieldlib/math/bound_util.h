// Small scalar helpers for bounds, shared by kernels, evaluators and nodes.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/interval.h"

namespace softtrace {

// a·b for bounds with 0·inf = 0: a factor that is flat over a box makes the product flat.
inline double flat_product(double a, double b) {
  return a == 0 || b == 0 ? 0 : a * b;
}

// The sign as -1, 0 or 1 (0 at 0: a symmetric subgradient at the kinks of |v|).
inline double sgn(double v) {
  return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
}

// sup |v| over an interval.
inline double magnitude(Interval a) {
  return std::max(std::abs(a.lo), std::abs(a.hi));
}

}  // namespace softtrace

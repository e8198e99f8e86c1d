// One coordinate term of the modulated gauges (docs/math.md §2.9, §2.10): for a linear coordinate
// s,
//   u(s) = [s - L]_+ / r_pos + [-s - L]_+ / r_neg,
// i.e. the one-branch planes [±s]_+/(t·a) of 002 Eqs. 15, 16, 18 with r_pos = t_{2i-1}·a and
// r_neg = t_{2i}·a, and the dead zone ζ_L of 002 Eq. 17 (L = 0 elsewhere). Only one half is ever
// non-zero, so Σ over both halves of u^n is u(s)^n. u is piecewise linear and non-decreasing in
// |s| on each side, which gives the exact image of an interval and the slope bounds below.
#pragma once

#include <algorithm>

#include "math/interval.h"

namespace softtrace {

struct OneSidedTerm {
  double r_pos = 1, r_neg = 1;  // radii on the s > 0 and s < 0 halves
  double dead = 0;              // half-length L of the zero zone |s| <= L

  // u(s), and du/ds into *du (0 inside the dead zone, including its ends: a subgradient).
  double value(double s, double* du) const {
    if (s > dead) {
      if (du) *du = 1 / r_pos;
      return (s - dead) / r_pos;
    }
    if (s < -dead) {
      if (du) *du = -1 / r_neg;
      return (-s - dead) / r_neg;
    }
    if (du) *du = 0;
    return 0;
  }
  // The image of s ∈ [lo, hi]; two roundings (subtract, divide) are covered by two ulps.
  Interval range(Interval s) const {
    double lo, hi;
    if (s.lo > dead) {
      lo = (s.lo - dead) / r_pos;
      hi = (s.hi - dead) / r_pos;
    } else if (s.hi < -dead) {
      lo = (-s.hi - dead) / r_neg;
      hi = (-s.lo - dead) / r_neg;
    } else {
      lo = 0;
      hi = std::max(std::max(0.0, s.hi - dead) / r_pos, std::max(0.0, -s.lo - dead) / r_neg);
    }
    return {std::max(0.0, iv::down(iv::down(lo))), iv::up(iv::up(hi))};
  }
  // |du/ds| everywhere, and over s ∈ [lo, hi] (0 when the interval stays in the dead zone).
  double slope() const { return 1 / std::min(r_pos, r_neg); }
  double slope(Interval s) const {
    double m = 0;
    if (s.hi > dead) m = 1 / r_pos;
    if (s.lo < -dead) m = std::max(m, 1 / r_neg);
    return m;
  }
  // The range of du/dt along a path where s ∈ [s] changes at a rate in [ds]: ds/r_pos where s may
  // be above the dead zone, -ds/r_neg where below it, 0 inside it (u is piecewise linear in s).
  // Each half's quotient is computed only where s may be on that half (a bounds pass along a
  // segment asks this of every gauge term, mostly with s on one side).
  Interval rate(Interval s, Interval ds) const {
    const auto up = [&] { return divided(ds, r_pos); };
    const auto down = [&] { return divided(-ds, r_neg); };
    if (s.lo > dead) return up();
    if (s.hi < -dead) return down();
    Interval d = 0.0;
    if (s.hi > dead) d = hull(d, up());
    if (s.lo < -dead) d = hull(d, down());
    return d;
  }
  // The s range of {u <= c} for c >= 0, widened by a relative 1e-12 against rounding.
  Interval below(double c) const {
    return {-(dead + c * r_neg) * (1 + 1e-12), (dead + c * r_pos) * (1 + 1e-12)};
  }
};

// A bound on an outer partial times an inner slope: a zero slope wins over an infinite partial
// (the inner term is constant over the box, so it contributes nothing).
inline double chain(double partial, double slope) {
  return slope == 0 ? 0.0 : partial * slope;
}

}  // namespace softtrace

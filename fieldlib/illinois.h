// The Illinois variant of regula falsi (Dowell and Jarratt 1971) on a bracket of a sign change:
// false position converges superlinearly on smooth roots, and an end kept twice in a row has its
// value halved so that the other end moves too. The callers choose the next point and when to
// stop; this only keeps the bracket.
#pragma once

namespace softtrace {

struct IllinoisBracket {
  double lo, f_lo;  // the end on the negative side
  double hi, f_hi;  // the end on the other side
  int side = 0;     // which end the last update replaced: -1 lo, +1 hi

  double false_position() const { return (lo * f_hi - hi * f_lo) / (f_hi - f_lo); }

  // Replaces the end on x's side (`upper`: hi's) with (x, fx).
  void update(double x, double fx, bool upper) {
    if (upper) {
      hi = x;
      f_hi = fx;
      if (side == +1) f_lo *= 0.5;
      side = +1;
    } else {
      lo = x;
      f_lo = fx;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
};

}  // namespace softtrace

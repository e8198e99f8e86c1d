// Radius transforms T of a distance d (docs/math.md §4.2–§4.9): the formulas with their partials,
// and "profiles" T(d; w) with one free parameter w that the soft-object node composes as
// P ∘ T ∘ d, with w constant (T_n, T_l, T_r) or w = w(d, f) from a modulation surface f
// (T_an, T_al, T_sn, T_sr, contour).
//
// Bounds, derived (not sampled):
// - Monotonicity. Every profile is non-decreasing in d, and in w it is non-decreasing for
//   d <= 0.5 and non-increasing for d >= 0.5 (T(0.5) = 0.5 for every w):
//   T_n linear branch: ∂T/∂w1 = -(d-0.5)/w1^2 <= 0; quadratic branch, e = 0.5-d in (0, w2/2]:
//   ∂T/∂w1 = e/w1^2 (1 - 2e/w2) >= 0 and ∂T/∂w2 = 2e^2/w2^2 (2/w2 - 1/w1) >= 0 (w2 <= 2 w1), and
//   the zero branch d < 0.5(1-w2) shrinks as w2 grows. T_l: ln T = ln2 (ln(2d)/ln(1+w1) - 1);
//   T_r: ln(1-T) = ln2 (ln(2(1-d))/ln(1+w2) - 1): the sign of ln(2d) (ln(2(1-d))) decides.
//   So the image of [d]×[w] is [T(d.lo, d.lo >= 0.5 ? w.hi : w.lo), T(d.hi, d.hi <= 0.5 ? w.hi :
//   w.lo)].
// - |∂T/∂d|: T_n: 1/w1 (linear), N_n' linear in d between 1/w1 and 2/w2 - 1/w1 ([TN-8]).
//   T_l: k T/d, with k = ln2/ln(1+w1); k >= 1 (w1 <= 1) gives (2md)^k/d <= 2 m^k <= 2 for d <= 0.5
//   and k/d <= 2k above, so 2k; otherwise k T.hi/d.lo (infinite at the skeleton: [TL-3]).
//   T_r: k y^k/u with u = 1-d, y = 2u/(1+w2) <= 1, k >= 1: <= k y/u = 2k/(1+w2).
// - inf ∂T/∂d (T_n, where [d] × [w] meets neither T = 0 nor T = 1): 1/w1 on the linear branch;
//   on the quadratic one, with τ = (1 - 2d)/w2 in [0, 1], ∂T/∂d = 1/w1 + 2A(d - 0.5) =
//   (1 - 2τ)/w1 + 2τ/w2 >= (1 - τ)/w1, as 2/w2 >= 1/w1 (w2 <= 2 w1), so at least
//   (1 - τ_hi)/w1_hi with τ_hi = (1 - 2 d_lo)/w2(w_lo) (w2 never falls as w1 grows).
// - |dT/dw| (total, w2 following w1 for T_an, w1 = w2 for T_sn): T_n linear branch
//   (d-0.5)/w1^2 <= min(d.hi-0.5, w1/2)/w1^2; quadratic branch e(1-2e/w2)/w1^2 <= min(e,
//   w2/8)/w1^2; under T_an ∂T/∂w2 vanishes (2/w2 - 1/w1 = 0 where w2 = 2 w1 < 1, dw2/dw1 = 0 where
//   w2 = 1); under T_sn it adds 2e^2/w^3 <= min(e/w^2, 1/(2w)). T_l: ∂T/∂w1 = -k T ln(2d)/((1+w1)
//   ln(1+w1)) and T |ln 2d| <= ln(1+w1) (d >= 0.5) or <= 1/(e k) (d < 0.5, max of y^k |ln y|), so
//   |∂T/∂w1| <= ln2/((1+w1) ln(1+w1)); T_r likewise with w2.
// - |dT/dw|/d (T_n with w1 >= 0, for the chain rule near the skeleton where |∇w| ~ 1/d):
//   quadratic branch e(w2-1+2d)/(w2 w1^2 d) <= 2e/(w2 w1^2) <= 1/w1^2; linear branch <= 2|∂T/∂w1|.
#pragma once

#include <limits>

#include "math/interval.h"

namespace softtrace {

struct TPartials {
  double d = 0, w1 = 0, w2 = 0;
};

// The formulas themselves, for any argument (no validation: the tests evaluate invalid ones).
// d is clamped at 0; partials are written when dT is non-null.
double transform_n(double d, double w1, double w2, TPartials* dT);  // 000 Eq. 13, 002 Eq. 10
double transform_l(double d, double w1, TPartials* dT);             // 002 Eq. 13
double transform_r(double d, double w2, TPartials* dT);             // 002 Eq. 14 (A3: 1 for d > 1)

// How w2 of T_n follows w = w1.
enum class W2Rule { Fixed, Double, Equal };  // T_n: given; T_an/contour: min(1, 2 w1); T_sn: w1

// T(d; w) with one free parameter: T_n (w1 = w, w2 by the rule), T_l (w1 = w) or T_r (w2 = w). A
// value, not a class hierarchy, so that a program instruction rebuilds it from its constants and
// switches on the kind instead of making a virtual call per point. The sup bounds hold over the
// box [d] × [w] (d.lo >= 0, w.lo > 0).
class RadiusProfile {
 public:
  enum class Kind { N, L, R };
  static constexpr int kConsts = 3;  // kind, rule, fixed w2

  RadiusProfile(Kind kind, W2Rule rule, double fixed_w2)
      : kind_(kind), rule_(rule), w2_(fixed_w2) {}
  void store(double* c) const;
  static RadiusProfile load(const double* c);

  // T and, when non-null, ∂T/∂d and the total dT/dw.
  double eval(double d, double w, double* Td, double* Tw) const;
  double slope_d(Interval d, Interval w) const;
  // inf ∂T/∂d over [d] × [w] (>= 0; 0 where not derived): T_n's, where [d] reaches neither flat
  // branch, is 1/w1 on the linear one and (1 - τ)/w1 or more on the quadratic one (header
  // comment). Along a segment it keeps T_d d' one-signed where d' is.
  double slope_d_min(Interval d, Interval w) const;
  double slope_w(Interval d, Interval w) const;
  // sup |dT/dw| / d; +inf when not derived for the profile.
  double slope_w_per_d(Interval d, Interval w) const;
  // {T < 1} = {d < outer_end(w)}: 0.5(1+w1) for T_n/T_l, 1 for T_r.
  double outer_end(double w) const { return kind_ == Kind::R ? 1 : 0.5 * (1 + w); }

  // The monotone image of [d] × [w] (header comment), padded for rounding.
  Interval image(Interval d, Interval w) const;

 private:
  // T_n's w2 as a function of w, and its derivative.
  double w2(double w) const;
  double dw2(double w) const;
  // The smallest w1 and w2 at which T_n's quadratic branch is reached from [d]: it needs
  // d >= 0.5(1 - w2), i.e. w2 >= 1 - 2 d.hi (T and all partials are 0 below it).
  struct Lows {
    double w1, w2;
  };
  Lows quadratic_w(Interval d, Interval w) const;
  double slope_d_n(Interval d, Interval w) const;
  double slope_w_n(Interval d, Interval w) const;
  double slope_w_per_d_n(Interval d, Interval w) const;
  double slope_d_l(Interval d, Interval w) const;
  double slope_d_r(Interval d, Interval w) const;

  Kind kind_;
  W2Rule rule_;
  double w2_;
};

RadiusProfile make_profile_n(W2Rule rule, double fixed_w2 = 1);  // 000 Eq. 13, 002 Eq. 10
RadiusProfile make_profile_l();                                  // 002 Eq. 13
RadiusProfile make_profile_r();                                  // 002 Eq. 14

}  // namespace softtrace

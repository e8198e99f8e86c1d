// P ∘ T ∘ d with w constant or from a modulation field f (000 Eqs. 13-15, 002 Eqs. 10-14,
// docs/math.md §4.2-§4.9): the kernels the model node (TransformedSoftObject, soft_object.cpp) and
// the RadiusTransform instruction share, so that both compute the same bits from d's and f's
// values, gradients and bounds. soft_object.h explains the bounds.
#pragma once

#include <vector>

#include "kernels/potentials.h"
#include "kernels/radius_transforms.h"
#include "math/box.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// Where w comes from: a constant, w1 = d/f - 1 (T_an, T_al, contour; 002 Eq. 11, 000 Eq. 15) or
// w2 = 1 - d/f (T_sn, T_sr; 002 Eq. 12).
enum class WSource { Constant, Outer, Inner };

struct TransformedPotential {
  PotentialKind P;
  RadiusProfile T;
  WSource src;
  double w = 1;                    // the constant w (WSource::Constant)
  double scale = 1, w_min = 1e-4;  // f = scale f_m; w's lower clamp
  double d_lipschitz = 0;          // d's global Lipschitz bound (the global bound's chain rule)
  Box support;                     // the node's region(0+, Above): the field is 0 outside

  // The constant pool's layout: P (op, s), T, src, w, scale, w_min, d_lipschitz, support (lo,
  // hi).
  static constexpr int kConsts = 2 + RadiusProfile::kConsts + 5 + 6;
  std::vector<double> constants() const;
  static TransformedPotential load(const double* c);

  // w from d > 0 and f (scaled), clamped to [w_min, w_max] (§4.9), with ∂w/∂d and ∂w/∂f.
  double parameter(double d, double f, double* wd, double* wf) const;

  // P(T(d, w)) and, where grad is non-null, its gradient from d's (gd) and the modulation's value
  // fm and gradient gfm (unscaled; read only for a modulated w and d > 0).
  double eval(double d, const Vec3& gd, double fm, const Vec3& gfm, Vec3* grad) const;

  struct Bounds {
    Interval d, f, r, w, T;  // f scaled; r = d/f, unclamped
    double Ld = 0, Lf = 0;   // d's and f's (unscaled) Lipschitz bounds, where asked for
  };
  // From [d] and [f_m] (unscaled; read only for a modulated w), with their Lipschitz bounds
  // (0 where the slope bound is not asked for). `r_known`, where given, also holds d/f over the
  // same points (along a segment, from its ends: RadiusTransformOp::ratio_along): [d]/[f] is
  // narrowed to it, since the two ignore that d and f move together.
  Bounds bounds(Interval d, double Ld, Interval fm, double Lf,
                Interval r_known = Interval::entire()) const;
  Interval interval(const Bounds& B) const { return P.interval(B.T); }
  // The Lipschitz bound over the box B was taken on (with d's and f's bounds).
  double slope_bound(const Bounds& B) const;
  double lipschitz() const;  // global: +inf for a modulated w (no global bound on ∇w)
  // Over the box B was taken on: an interval holding d(P ∘ T ∘ d)/dt along a segment where d's
  // own derivative lies in `dd` and the modulation's (unscaled) in `dfm`. It is P'(T) dT/dt, with
  // P' in [-|P'|, 0] (P never rises), dT/dt = T_d d' + T_w w', T_d in [inf T_d, sup T_d] (T never
  // falls with d; RadiusProfile::slope_d_min) and T_w of the sign radius_transforms.h gives it on
  // either side of d = 0.5; w' = 0 where w is clamped, else ±(d' - (d/f) f')/f (w1 = d/f - 1, w2 =
  // 1 - d/f). Entire where f may reach 0.
  Interval slope_along(const Bounds& B, Interval dd, Interval dfm) const;

  bool outside_support(const Box& b) const {
    return support.bounded() && support.intersected(b).empty();
  }
};

}  // namespace softtrace

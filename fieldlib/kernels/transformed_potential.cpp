#include "kernels/transformed_potential.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/bound_util.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// w1 = d/f - 1 is capped here where f -> 0 away from the skeleton; T_n/T_l are then ~0.5 on the
// outer branch, the limit w1 -> infinity.
constexpr double kWMax = 1e6;

}  // namespace

std::vector<double> TransformedPotential::constants() const {
  std::vector<double> c(kConsts);
  c[0] = static_cast<double>(P.type);
  c[1] = P.s;
  T.store(&c[2]);
  double* k = &c[2 + RadiusProfile::kConsts];
  k[0] = static_cast<double>(src);
  k[1] = w;
  k[2] = scale;
  k[3] = w_min;
  k[4] = d_lipschitz;
  for (int i = 0; i < 3; ++i) {
    k[5 + i] = support.lo[i];
    k[8 + i] = support.hi[i];
  }
  return c;
}

TransformedPotential TransformedPotential::load(const double* c) {
  const double* k = c + 2 + RadiusProfile::kConsts;
  Box support;
  for (int i = 0; i < 3; ++i) {
    support.lo[i] = k[5 + i];
    support.hi[i] = k[8 + i];
  }
  return {{static_cast<PotentialType>(static_cast<int>(c[0])), c[1]},
          RadiusProfile::load(c + 2),
          static_cast<WSource>(static_cast<int>(k[0])),
          k[1],
          k[2],
          k[3],
          k[4],
          support};
}

double TransformedPotential::parameter(double d, double f, double* wd, double* wf) const {
  *wd = *wf = 0;
  const double hi = src == WSource::Outer ? kWMax : 1;
  if (f <= 0) return src == WSource::Outer ? kWMax : w_min;  // condition (c) violated
  const double sign = src == WSource::Outer ? 1 : -1;
  const double v = src == WSource::Outer ? d / f - 1 : 1 - d / f;
  if (v <= w_min) return w_min;
  if (v >= hi) return hi;
  *wd = sign / f;
  *wf = -sign * d / (f * f);
  return v;
}

double TransformedPotential::eval(double d, const Vec3& gd, double fm, const Vec3& gfm,
                                  Vec3* grad) const {
  if (d <= 0) {  // the skeleton: T = 0 (§4.9), P'(0) = 0
    if (grad) *grad = {};
    return P.eval(0, nullptr);
  }
  double v = w, wd = 0, wf = 0;
  Vec3 gf;
  if (src != WSource::Constant) {
    const double f = scale * fm;
    v = parameter(d, f, &wd, &wf);
    gf = gfm * scale;
  }
  double Td, Tw, dP;
  const double t = T.eval(d, v, &Td, &Tw);
  const double value = P.eval(t, grad ? &dP : nullptr);
  if (grad) {
    if (dP == 0) {
      *grad = {};
    } else {
      const Vec3 gT = gd * (Td + Tw * wd) + gf * (Tw * wf);
      *grad = gT * dP;
    }
  }
  return value;
}

double TransformedPotential::lipschitz() const {
  if (src != WSource::Constant) return kInf;
  const double s = T.slope_d({0, kInf}, Interval(w));
  return flat_product(P.lipschitz(), flat_product(s, d_lipschitz));
}

double TransformedPotential::slope_bound(const Bounds& B) const {
  if (B.T.hi <= 0) return 0;  // T = 0: P(0) over the whole box
  const double LP = P.lipschitz(B.T);
  if (LP == 0) return 0;
  const double dterm = flat_product(T.slope_d(B.d, B.w), B.Ld);
  if (src == WSource::Constant) return std::min(lipschitz(), flat_product(LP, dterm));
  const double sw = T.slope_w(B.d, B.w);
  double wterm = 0;
  if (sw > 0) {
    const double Lf = scale * B.Lf;
    const double G1 = B.f.lo > 0 ? B.Ld / B.f.lo + B.d.hi * Lf / (B.f.lo * B.f.lo) : kInf;
    const double G2 = B.r.hi * (B.Ld + B.r.hi * Lf);
    wterm = std::min(flat_product(sw, G1), flat_product(T.slope_w_per_d(B.d, B.w), G2));
  }
  return flat_product(LP, (dterm + wterm) * (1 + 1e-12));
}

Interval TransformedPotential::slope_along(const Bounds& B, Interval dd, Interval dfm) const {
  // T constant over the box (0, or 1 by [TA-1]): so is the field.
  if (B.T.hi <= 0 || B.T.lo == B.T.hi) return Interval(0);
  const double LP = P.lipschitz(B.T);
  if (LP == 0) return Interval(0);
  // T_d in [inf, sup]: a positive inf keeps T_d d' one-signed where d' is, so that the w' term
  // (whose interval spans 0 near the surface, where d and f move together) cannot flip it.
  Interval dT = Interval(T.slope_d_min(B.d, B.w), T.slope_d(B.d, B.w)) * dd;
  if (src != WSource::Constant) {
    if (!(B.f.lo > 0)) return Interval::entire();
    const Interval dr = (dd - B.r * (dfm * Interval(scale))) / B.f;  // (d/f)' = (d' - r f')/f
    const Interval dw = hull(src == WSource::Outer ? dr : -dr, Interval(0));
    const double sw = T.slope_w(B.d, B.w);
    const Interval Tw = B.d.hi <= 0.5   ? Interval(0, sw)
                        : B.d.lo >= 0.5 ? Interval(-sw, 0)
                                        : Interval(-sw, sw);
    dT = dT + Tw * dw;
  }
  // P' in [-LP, 0] times dT: an end of dT's sign gives an end of exactly 0 (outward rounding of
  // 0 * x would make it a subnormal of the wrong sign, and the tracer reads a one-signed slope
  // from the sign alone).
  if (std::isnan(dT.lo) || std::isnan(dT.hi)) return Interval::entire();
  const double rise = std::max(0.0, dT.hi), fall = std::min(0.0, dT.lo);
  return {rise > 0 ? iv::down(-LP * rise * (1 + 1e-12)) : 0.0,
          fall < 0 ? iv::up(-LP * fall * (1 + 1e-12)) : 0.0};
}

TransformedPotential::Bounds TransformedPotential::bounds(Interval d, double Ld, Interval fm,
                                                          double Lf, Interval r_known) const {
  Bounds B;
  B.Ld = Ld;
  B.d = {std::max(0.0, d.lo), std::max(0.0, d.hi)};
  if (src == WSource::Constant) {
    B.w = Interval(w);
    B.T = T.image(B.d, B.w);
    return B;
  }
  B.Lf = Lf;
  B.f = {iv::down(scale * fm.lo), iv::up(scale * fm.hi)};
  if (B.f.lo > 0) {
    B.r = B.d / B.f;
  } else {  // f can reach 0 (or below, where w is capped): no upper bound on d/f
    B.r = {B.f.hi > 0 ? iv::down(B.d.lo / B.f.hi) : kInf, kInf};
  }
  const double r_lo = std::max(B.r.lo, r_known.lo), r_hi = std::min(B.r.hi, r_known.hi);
  if (r_lo <= r_hi) B.r = {r_lo, r_hi};  // (never empty but through rounding: keep [d]/[f] then)
  const auto clamp = [&](double v, double hi) { return std::min(std::max(v, w_min), hi); };
  if (src == WSource::Outer) {
    B.w = {clamp(iv::down(B.r.lo - 1), kWMax), clamp(iv::up(B.r.hi - 1), kWMax)};
    // [TA-1] with the clamp: T = 1 where d >= 0.5(1+w_min) and f >= 0.5.
    if (B.d.lo > 0.5 * (1 + w_min) * (1 + 1e-12) && B.f.lo > 0.5 * (1 + 1e-12)) {
      B.T = Interval(1);
      return B;
    }
  } else {
    B.w = {clamp(iv::down(1 - B.r.hi), 1), clamp(iv::up(1 - B.r.lo), 1)};
    // [TS-1] with the clamp: T = 0 where d < 0.5(1-w_min) and f < 0.5.
    if (B.d.hi < 0.5 * (1 - w_min) * (1 - 1e-12) && B.f.hi < 0.5 * (1 - 1e-12)) {
      B.T = Interval(0);
      return B;
    }
  }
  B.T = T.image(B.d, B.w);
  return B;
}

}  // namespace softtrace

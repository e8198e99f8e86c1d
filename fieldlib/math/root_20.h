// s^(1/20) for the power sums of the papers' cubes and bars (n = 20), whose sums relative to their
// largest term lie in [1, k] for k terms: std::pow took a tenth of Fig. 12(b)'s instructions and a
// sixth of its time for this one root. Within an ulp of the exact root (a faithful rounding, as
// std::pow's is within about half of one): the power sums' bounds widen their roots by 1e-13
// relative, far above it.
#pragma once

#include <cmath>

namespace softtrace {

// [1, 4): a polynomial in the mantissa's place in [1, 2) (a Chebyshev interpolant of degree 8 of
// m^(1/20), within 1.8e-9 relative), times 2^(1/20) for [2, 4), then one Newton step r - (r^20 -
// s) / (20 r^19), which takes an error e to about 9.5 e^2 (3e-17) and adds under half an ulp of
// rounding to its own. Elsewhere (and NaN) std::pow.
inline double root_20(double s) {
  if (!(s >= 1 && s < 4)) return std::pow(s, 1 / 20.0);
  const bool upper = s >= 2;
  const double m = upper ? s * 0.5 : s;  // exact
  const double u = (m - 1.5) * 2;        // in [-1, 1), exact
  // Estrin's order, not Horner's: the root sits on its callers' critical path, and pairs of
  // terms then wait on u^2, u^4 and u^8 (about 7 multiplications deep rather than 16).
  const double u2 = u * u, u4 = u2 * u2, u8 = u4 * u4;
  const double c01 = 0x1.053e2ff624368p+0 + 0x1.16a8afff73ecbp-6 * u;
  const double c23 = -0x1.60f7c0a6cee39p-9 + 0x1.31fb3d1346aaap-11 * u;
  const double c45 = -0x1.2ce5e00c8aaaap-13 + 0x1.38931c50ce38ep-15 * u;
  const double c67 = -0x1.576a1a9800000p-17 + 0x1.e25ddcc8e38e3p-19 * u;
  double r = (c01 + c23 * u2) + (c45 + c67 * u2) * u4 - 0x1.190bfc271c71cp-20 * u8;
  if (upper) r *= 0x1.09071f3e983adp+0;  // 2^(1/20)
  // r^19 and r^20 from r^4 and r^16 side by side, not r^20 as r^19 r.
  const double r2 = r * r, r4 = r2 * r2, r8 = r4 * r4, r16 = r8 * r8;
  const double r19 = r2 * r * r16, r20 = r4 * r16;
  return r - (r20 - s) / (20 * r19);
}

}  // namespace softtrace

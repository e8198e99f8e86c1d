// The spherical product m(h(u_x, u_y), u_z), h = (u_x^n1 + u_y^n1)^(1/n1),
// m = (h^n2 + u_z^n2)^(1/n2), over the one-sided terms u of one_sided.h (the superquadric and the
// super-elliptic cylinder, docs/math.md §2.6, §2.9-2.10) as kernels shared by the model node
// (distances_gauge.cpp) and the program's SphericalProduct instruction, so both compute the same
// bits. Bounds over a box: ∇f = (∂m/∂h·∂h/∂u_x·u_x', ∂m/∂h·∂h/∂u_y·u_y', ∂m/∂u_z·u_z') with
// ∇h ⟂ z; each partial is bounded by power_sum_partial_bound, each slope by the signs the box
// reaches, and the global bound (nested gauge_lipschitz) caps the result.
#pragma once

#include <algorithm>
#include <cmath>

#include "kernels/gauge.h"
#include "kernels/one_sided.h"
#include "math/box.h"

namespace softtrace {

struct SphericalProductParams {
  OneSidedTerm t[3];  // u_x, u_y, u_z
  double n1, n2, global_L;
};

inline double spherical_product(const SphericalProductParams& m, const Vec3& p, Vec3* grad) {
  double dx, dy, dz, dh[2], dm[2];
  const double uh[2] = {m.t[0].value(p.x, &dx), m.t[1].value(p.y, &dy)};
  const double um[2] = {power_sum(uh, 2, m.n1, grad ? dh : nullptr), m.t[2].value(p.z, &dz)};
  const double f = power_sum(um, 2, m.n2, grad ? dm : nullptr);
  if (grad) *grad = {dm[0] * dh[0] * dx, dm[0] * dh[1] * dy, dm[1] * dz};
  return f;
}

// The value interval and the Lipschitz bound over `b` from one computation of the terms. With
// `rate` (the local coordinates' rates along a segment in `b`), also the range of df/dt along it
// into *slope: dm/dt = ∂m/∂h·dh/dt + ∂m/∂u_z·u_z', dh/dt = Σ ∂h/∂u_i·u_i', each a power_sum_slope
// (not capped by the Lipschitz bound).
inline void spherical_product_bounds(const SphericalProductParams& m, const Box& b, Interval* value,
                                     double* lipschitz, const Interval* rate = nullptr,
                                     Interval* slope = nullptr) {
  const Interval uh[2] = {m.t[0].range(b.axis(0)), m.t[1].range(b.axis(1))};
  const Interval um[2] = {power_sum(uh, 2, m.n1), m.t[2].range(b.axis(2))};
  const Interval f = power_sum(um, 2, m.n2);
  *value = f;
  if (!lipschitz) return;
  // The partials' upper ends: the Lipschitz bound's, and the slope's again (not recomputed).
  const double ph[2] = {power_sum_partial_bound(uh[0], um[0], m.n1),
                        power_sum_partial_bound(uh[1], um[0], m.n1)};
  const double pm[2] = {power_sum_partial_bound(um[0], f, m.n2),
                        power_sum_partial_bound(um[1], f, m.n2)};
  const double bx = chain(ph[0], m.t[0].slope(b.axis(0)));
  const double by = chain(ph[1], m.t[1].slope(b.axis(1)));
  const double gh = chain(pm[0], std::sqrt(bx * bx + by * by));
  const double gz = chain(pm[1], m.t[2].slope(b.axis(2)));
  const double L = std::sqrt(gh * gh + gz * gz) * (1 + 1e-13);
  *lipschitz = std::isnan(L) ? m.global_L : std::min(m.global_L, L);
  if (!rate) return;
  const Interval duh[2] = {m.t[0].rate(b.axis(0), rate[0]), m.t[1].rate(b.axis(1), rate[1])};
  const Interval dum[2] = {power_sum_slope(uh, duh, 2, um[0], m.n1, ph),
                           m.t[2].rate(b.axis(2), rate[2])};
  *slope = power_sum_slope(um, dum, 2, f, m.n2, pm);
}

}  // namespace softtrace

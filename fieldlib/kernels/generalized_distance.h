// The (modulated) generalized distance function (docs/math.md §2.7, §2.10) as kernels shared by
// the model node (distances_planes.cpp) and the program's GenDistance instruction, so both compute
// the same bits:
//   f = (Σ_i u_i^n)^(1/n), u_i = [X·n_i]_+/(t_{2i-1} a_i) + [-X·n_i]_+/(t_{2i} a_i)
//   — 000 Eq. 4, 002 Eq. 16 with AMBIGUITY A2 (R3).
// The normals n_i are unit vectors. The parameters live in one array, the instruction's constants
// (and the node's own copy): n, σ (below), the global Lipschitz bound, then per normal n_i (3
// numbers) and its one-sided term's r_pos, r_neg and dead zone.
//
// Bounds. ∇f = N^T v with N the unit normals as rows and v_i = ∂f/∂u_i · u_i'. For n >= 1 the
// partials have l_q norm 1 (1/n + 1/q = 1) and |u_i'| <= r_i = 1/(a_i min t), so
//   |∇f| <= Σ ∂_i r_i <= ||r||_n                                      (Hölder), and
//   |∇f| <= σ_max(N)·|v|_2 <= σ_max(N)·gauge_lipschitz(r)             (l_q -> l_2 norm of diag r),
// with σ_max(N)^2 = λ_max(N^T N) <= min(trace, max row sum). With the axes as normals σ = 1 and
// the second bound is the LP metric's. Over a box, ∂_i and u_i' are bounded from the intervals of
// X·n_i, which the caller gives (dot_range over a box; the segment pass takes them along a
// segment, where X·n_i is affine).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "kernels/gauge.h"
#include "kernels/one_sided.h"
#include "kernels/planes.h"
#include "math/box.h"
#include "math/interval.h"
#include "math/scratch.h"
#include "math/vec.h"

namespace softtrace {

// Where the parameters sit in the constants: the header, then kGdStride numbers per normal.
constexpr int kGdHeader = 3, kGdStride = 6;

struct GeneralizedDistanceParams {
  const double* c;  // n, σ, global L, then per normal: n_i.x, n_i.y, n_i.z, r_pos, r_neg, dead
  int k;            // the number of normals

  double n() const { return c[0]; }
  double sigma() const { return c[1]; }
  double global_L() const { return c[2]; }
  Vec3 normal(int i) const {
    const double* t = c + kGdHeader + kGdStride * i;
    return {t[0], t[1], t[2]};
  }
  OneSidedTerm term(int i) const {
    const double* t = c + kGdHeader + kGdStride * i;
    return {t[3], t[4], t[5]};
  }
};

// The parameter array for unit `normals` and their `terms` with exponent n: σ and the global
// Lipschitz bound (infinite for n < 1) computed as the class comment says.
inline std::vector<double> generalized_distance_constants(const std::vector<Vec3>& normals,
                                                          const std::vector<OneSidedTerm>& terms,
                                                          double n) {
  double G[3][3] = {};
  for (const Vec3& v : normals)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) G[i][j] += v[i] * v[j];
  double trace = 0, row_sum = 0;
  for (int i = 0; i < 3; ++i) {
    trace += G[i][i];
    row_sum = std::max(row_sum, std::abs(G[i][0]) + std::abs(G[i][1]) + std::abs(G[i][2]));
  }
  const double sigma = std::sqrt(std::min(trace, row_sum)) * (1 + 1e-12);
  double global_L = std::numeric_limits<double>::infinity();
  if (n >= 1) {
    std::vector<double> r;
    for (const auto& t : terms) r.push_back(t.slope());
    const int k = static_cast<int>(r.size());
    global_L =
        std::min(power_sum(r.data(), k, n, nullptr), sigma * gauge_lipschitz(r.data(), k, n));
    global_L *= 1 + 1e-12;
  }
  std::vector<double> c{n, sigma, global_L};
  for (size_t i = 0; i < normals.size(); ++i) {
    const Vec3& v = normals[i];
    c.insert(c.end(), {v.x, v.y, v.z, terms[i].r_pos, terms[i].r_neg, terms[i].dead});
  }
  return c;
}

// f(p), and ∇f into *grad when non-null.
inline double generalized_distance(const GeneralizedDistanceParams& m, const Vec3& p, Vec3* grad) {
  const int k = m.k;
  Scratch<double> u(k), du(k), dfdu(k);
  for (int i = 0; i < k; ++i) u[i] = m.term(i).value(dot(p, m.normal(i)), &du[i]);
  const double f = power_sum(u.data(), k, m.n(), grad ? dfdu.data() : nullptr);
  if (grad) {
    *grad = {};
    for (int i = 0; i < k; ++i) *grad += m.normal(i) * (dfdu[i] * du[i]);
  }
  return f;
}

// The value interval, and the Lipschitz bound into *lipschitz when non-null, where X·n_i lies in
// s[i]; the terms' ranges go to u[i] (both arrays of m.k).
inline void generalized_distance_bounds(const GeneralizedDistanceParams& m, const Interval* s,
                                        Interval* u, Interval* value, double* lipschitz) {
  const int k = m.k;
  const double e = m.n();
  for (int i = 0; i < k; ++i) u[i] = m.term(i).range(s[i]);
  const Interval f = power_sum(u, k, e);
  *value = f;
  if (!lipschitz) return;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < k; ++i) {
    const double g = chain(power_sum_partial_bound(u[i], f, e), m.term(i).slope(s[i]));
    sum += g;
    sum2 += g * g;
  }
  const double L = std::min(sum, m.sigma() * std::sqrt(sum2)) * (1 + 1e-13);
  *lipschitz = std::isnan(L) ? m.global_L() : std::min(m.global_L(), L);
}

// The same over a box: X·n_i over it by dot_range.
inline void generalized_distance_bounds(const GeneralizedDistanceParams& m, const Box& b,
                                        Interval* value, double* lipschitz) {
  Scratch<Interval> s(m.k), u(m.k);
  for (int i = 0; i < m.k; ++i) s[i] = dot_range(b, m.normal(i));
  generalized_distance_bounds(m, s.data(), u.data(), value, lipschitz);
}

}  // namespace softtrace

// The scalar maths of the generalized blend BT_k of 003 (docs/math.md §6.1, §6.2, §7), zero
// convention: BT_k(x) = h_p with HT_k(x_1 - m_1 h_p, ..., x_k - m_k h_p) = 0, the union base HT_k
// being Hoffmann's conic H_2 (§7.2) or the hyper-ellipsoid (§7.3). Nodes (blends_bt.cpp) and tests
// share these functions.
//
// Facts the nodes' bounds rest on (docs/math.md §7.1, §8; tested in
// tests/fieldlib/kernels/test_bt.cpp):
// - [BT-5] ∂BT/∂x_i >= 0 and [BT-2] Σ m_i ∂BT/∂x_i = 1.
// - h_lo(x) = min_i (x_i - r_i)/m_i <= BT(x) <= h_hi(x) = min_i x_i/m_i ([BT-3], §7.3 bracket;
//   for the conic, u = x - m·BT lies in Q = [0,r1]x[0,r2] in region II and BT = h_hi outside).
// - Infinite arguments: x_i = -inf gives BT = -inf (BT <= x_i/m_i); x_i = +inf drops argument i
//   (its hyper-ellipsoid term is 0 and the conic falls back to the other x_j/m_j); all +inf
//   gives +inf. So interval endpoints may be infinite.
// - Accuracy: the conic root is the closed form (a few ulps of the inputs' magnitude); Newton's
//   method stops at |T(h)| <= 1e-14 (or a step of 1e-14 relative, below h's rounding), and at the
//   root T'(h) = Σ p_i m_i/r_i q_i^(p_i-1) >= min_i(p_i m_i/r_i)/k (some q_i^(p_i) >= 1/k, so
//   q_i^(p_i-1) >= 1/k), so |h - h*| <= 1e-14·k·max_i r_i/m_i plus rounding of T, O(k·eps·(|x|/m +
//   |h|)). `value_tolerance` is a bound on that error with a wide safety factor (1e-9 relative);
//   interval enclosures are padded by it.
// - Cost: Newton's method from h_hi (T is convex) took 3.61 iterations on average (max 9) over
//   the 36 367 of 60 000 random inputs (k = 2..6) that needed it, the Illinois Regula Falsi before
//   it 7.05 (max 18); the rest are non-blending and return h_hi after one evaluation of T
//   (tests/fieldlib/kernels/test_bt.cpp, RootResidualAndIterationCounts).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "math/bound_util.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// Hoffmann's conic B_H(u) (000 Eq. 7, 003 H_2, docs/math.md §6.1); r1, r2 > 0, p < r1 r2.
double hoffmann_conic(double u1, double u2, double r1, double r2, double p);

// BT_2 on the conic base (003 Eq. 4 with the corrected a of R8, docs/math.md §7.2): the "+" root in
// (h2, h1] in region II, min(x1/m1, x2/m2) outside. dx (nullable) gets ∂BT/∂x_i by the implicit
// function theorem (§7.5); e_j/m_j for the arg-min j outside region II.
double bt2_conic(const double x[2], double r1, double r2, double p, const double m[2],
                 double dx[2]);
bool conic_region_ii(const double x[2], double r1, double r2, const double m[2]);

// ∂BT_2/∂(r1, r2, p, m1, m2) at x (docs/math.md §7.5, [GR-3]); zero for r and p outside region II.
struct ConicParameterDerivatives {
  double r1 = 0, r2 = 0, p = 0, m1 = 0, m2 = 0;
};
ConicParameterDerivatives bt2_conic_parameter_derivatives(const double x[2], double r1, double r2,
                                                          double p, const double m[2]);

// T(h) = Σ [(r_i - x_i + m_i h)/r_i]_+^(p_i) - 1 of the hyper-ellipsoidal base (003 Eq. 5, R10).
double hyper_T(const double* x, int k, const double* r, const double* p, const double* m, double h);
// T(h) (hyper_T's bits) and T'(h) = Σ p_i (m_i/r_i) t_i^(p_i-1) over the positive terms t_i.
double hyper_T_slope(const double* x, int k, const double* r, const double* p, const double* m,
                     double h, double* slope);
// BT_k on the hyper-ellipsoidal base (docs/math.md §7.3): Newton's method from h_hi, kept in
// (h_lo, h_hi]; returns h_hi when T(h_hi) <= 0. dx (nullable) gets the IFT partials; iterations
// (nullable) the number of Newton steps taken (0 when h_hi is returned directly).
double bt_hyper(const double* x, int k, const double* r, const double* p, const double* m,
                double* dx, int* iterations);

// h_lo and h_hi of docs/math.md §7.3 (any base): the bracket of BT.
double bt_lower(const double* x, int k, const double* r, const double* m);
double bt_upper(const double* x, int k, const double* m);

// Bound on |computed BT(x) - exact BT(x)| for ranges r and weights m (see the header comment).
// Inline, as bt_can_be_active: the Bt instruction's bounds call both on every pass.
inline double bt_value_tolerance(const double* x, int k, double value, const double* r,
                                 const double* m) {
  if (!std::isfinite(value)) return 0;
  double scale = std::abs(value);
  for (int i = 0; i < k; ++i)
    if (std::isfinite(x[i])) scale = std::max(scale, (std::abs(x[i]) + r[i]) / m[i]);
  return 1e-9 * scale + std::numeric_limits<double>::denorm_min();
}

// Whether ∂_iBT can be non-zero where x_j ∈ [lo_j, hi_j]: it is zero wherever x_i - M_i·min_{j≠i}
// x_j/M_j >= P_i (the hyper-ellipsoid term i is 0 since h <= min_j x_j/M_j; for the conic, x is
// outside region II with another arg-min), checked with the interval ends, P_i <= P_hi[i] and
// M_i ∈ [m_i, M_hi[i]] (without bulge elimination P_hi = r, M_hi = m).
inline bool bt_can_be_active(int i, int k, const double* lo, const double* hi, const double* P_hi,
                             const double* m, const double* M_hi) {
  double others = std::numeric_limits<double>::infinity();  // >= min_{j≠i} x_j/M_j over the box
  for (int j = 0; j < k; ++j)
    if (j != i) others = std::min(others, iv::up(hi[j] / (hi[j] >= 0 ? m[j] : M_hi[j])));
  const double reach = iv::up(flat_product(others >= 0 ? M_hi[i] : m[i], others));
  return !(iv::down(lo[i] - reach) > P_hi[i]);
}

// A blending operator: the base with its parameters plus the weights m (003 Eq. 2).
class BtOperator {
 public:
  static BtOperator conic(double r1, double r2, double p, std::vector<double> m);
  static BtOperator hyperellipsoid(std::vector<double> r, std::vector<double> p,
                                   std::vector<double> m);

  int k() const { return static_cast<int>(m_.size()); }
  bool is_conic() const { return conic_; }
  const std::vector<double>& r() const { return r_; }  // conic: {r1, r2}
  const std::vector<double>& m() const { return m_; }
  double conic_p() const { return p_.empty() ? 0 : p_[0]; }
  const std::vector<double>& p() const { return p_; }  // the hyper-ellipsoid: p_i; conic: {p}

  double operator()(const double* x, double* dx) const { return eval(x, r_.data(), m_.data(), dx); }
  // With the ranges r and weights m replaced (bulge elimination's position functions, §7.6).
  double eval(const double* x, const double* r, const double* m, double* dx) const;
  // ∂BT/∂r_i (docs/math.md §7.5) into dr at x with ranges r and weights m, given h = BT(x) and
  // dx = ∂BT/∂x_i there. Hyper-ellipsoid: ∂T/∂r_i = p_i q_i^(p_i-1) u_i/r_i² with u = x - m h,
  // so ∂BT/∂r_i = -∂_iBT·u_i/r_i; the conic: bt2_conic_parameter_derivatives. Zero outside the
  // blend (u_j = 0 for the arg-min j, ∂_iBT = 0 for the others).
  void range_derivatives(const double* x, const double* r, const double* m, double h,
                         const double* dx, double* dr) const;

  // Bound on |computed BT(x) - exact BT(x)| for the given r, m (see the header comment).
  double value_tolerance(const double* x, double value, const double* r, const double* m) const;

 private:
  bool conic_ = false;
  std::vector<double> r_, p_, m_;  // conic: p_ = {p}
};

// Bulge elimination (003 §5, docs/math.md §7.6) for k = 2 with union operands g_1, g_2:
// cosθ = ∇g1·∇g2/(|∇g1||∇g2|) (0 when a gradient vanishes: the ranges stay at r_i(1 + ω) and
// M_i = m_i), G = |∇g1|/|∇g2|, P_i = r_i(1 - cosθ + ω), M_i per the cases of §7.6.
struct BulgeParameters {
  double cos_theta = 0, P[2] = {0, 0}, M[2] = {0, 0};
};
BulgeParameters bulge_parameters(const Vec3& grad_g1, const Vec3& grad_g2, const double r[2],
                                 const double m[2], double omega);
// M_1, M_2 of §7.6 for a given G and cosθ.
void bulge_weights(double m1, double m2, double G, double cos_theta, double M[2]);

// What bounding P_i and M_i over a box needs from each union operand g_i = σ_i f_i (node.h):
// ∇g_i at the box centre, bounds grad_lo <= |∇g_i| <= grad_hi and the Hessian bound.
struct BulgeOperand {
  Vec3 centre_gradient;
  double grad_lo = 0, grad_hi = 0, hessian = 0;
};
// Over a box of half-diagonal `radius` (derivation in blends_bt.h): cosθ's range and a bound on
// |∇cosθ|, the ranges of P_i and the upper ends of M_i, and bounds on |∇M_i|. Unknown slopes
// give dcos = dM = +inf, cosθ ∈ [-1, 1] and M_hi = +inf where G is unbounded.
struct BulgeBox {
  double cos_lo = -1, cos_hi = 1, dcos = 0;
  double P_lo[2] = {0, 0}, P_hi[2] = {0, 0}, M_hi[2] = {0, 0}, dM[2] = {0, 0};
};
BulgeBox bulge_box(const BulgeOperand g[2], double radius, const double r[2], const double m[2],
                   double omega);

}  // namespace softtrace

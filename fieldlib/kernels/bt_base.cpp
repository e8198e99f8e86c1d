#include "kernels/bt_base.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/bound_util.h"
#include "math/interval.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ∂BT/∂x = e_j/m_j for the arg-min j of x_i/m_i: the gradient of min where BT = h_hi.
void argmin_gradient(const double* x, int k, const double* m, double* dx) {
  int j = 0;
  for (int i = 1; i < k; ++i)
    if (x[i] / m[i] < x[j] / m[j]) j = i;
  for (int i = 0; i < k; ++i) dx[i] = i == j ? 1 / m[i] : 0;
}

}  // namespace

double hoffmann_conic(double u1, double u2, double r1, double r2, double p) {
  const double t = r2 * u1 + r1 * u2 - r1 * r2;
  return t * t + 2 * (p - r1 * r2) * u1 * u2;
}

bool conic_region_ii(const double x[2], double r1, double r2, const double m[2]) {
  return m[1] * x[0] - m[0] * (x[1] - r2) > 0 && m[1] * (x[0] - r1) - m[0] * x[1] < 0;
}

double bt2_conic(const double x[2], double r1, double r2, double p, const double m[2],
                 double dx[2]) {
  const double h1 = std::min(x[0] / m[0], x[1] / m[1]);
  if (!conic_region_ii(x, r1, r2, m)) {  // also every infinite argument
    if (dx) argmin_gradient(x, 2, m, dx);
    return h1;
  }
  const double x1 = x[0], x2 = x[1], m1 = m[0], m2 = m[1];
  const double a = r2 * r2 * m1 * m1 + r1 * r1 * m2 * m2 + 2 * p * m1 * m2;  // R8
  const double b =
      2 * ((r2 - x2) * r1 * r1 * m2 + (r1 - x1) * r2 * r2 * m1 - (x1 * m2 + x2 * m1) * p);
  const double c = hoffmann_conic(x1, x2, r1, r2, p);
  const double sq = std::sqrt(std::max(b * b - 4 * a * c, 0.0));
  // The "+" root (R9) without cancellation (§6.3.2); a = 0 forces b > 0 in region II.
  double h = b > 0 ? 2 * c / (-b - sq) : (-b + sq) / (2 * a);
  const double h2 = (r1 * x2 + r2 * x1 - r1 * r2) / (r1 * m2 + r2 * m1);  // the chord
  if (!std::isfinite(h)) h = h1;  // only a = 0 with b <= 0, impossible in exact arithmetic
  h = std::min(std::max(h, h2), h1);
  if (dx) {
    const double u1 = x1 - m1 * h, u2 = x2 - m2 * h;
    const double g1 = 2 * r2 * r2 * (u1 - r1) + 2 * p * u2,
                 g2 = 2 * r1 * r1 * (u2 - r2) + 2 * p * u1;
    const double den = m1 * g1 + m2 * g2;  // -T'(h) < 0 at the simple root
    if (den < 0) {
      dx[0] = std::max(0.0, g1 / den);
      dx[1] = std::max(0.0, g2 / den);
    } else {
      argmin_gradient(x, 2, m, dx);
    }
  }
  return h;
}

ConicParameterDerivatives bt2_conic_parameter_derivatives(const double x[2], double r1, double r2,
                                                          double p, const double m[2]) {
  double dx[2];
  const double h = bt2_conic(x, r1, r2, p, m, dx);
  ConicParameterDerivatives d;
  d.m1 = -h * dx[0];  // from BT(x; m) and the translation identity, everywhere
  d.m2 = -h * dx[1];
  if (!conic_region_ii(x, r1, r2, m)) return d;
  const double u1 = x[0] - m[0] * h, u2 = x[1] - m[1] * h;
  const double g1 = 2 * r2 * r2 * (u1 - r1) + 2 * p * u2, g2 = 2 * r1 * r1 * (u2 - r2) + 2 * p * u1;
  const double den = m[0] * g1 + m[1] * g2;
  if (!(den < 0)) return d;
  d.r1 = (2 * r1 * u2 * u2 + 2 * r2 * r2 * r1 - 2 * r2 * r2 * u1 - 4 * r1 * r2 * u2) / den;
  d.r2 = (2 * r2 * u1 * u1 + 2 * r1 * r1 * r2 - 4 * r1 * r2 * u1 - 2 * r1 * r1 * u2) / den;
  d.p = 2 * u1 * u2 / den;
  return d;
}

double hyper_T(const double* x, int k, const double* r, const double* p, const double* m,
               double h) {
  double s = 0;
  for (int i = 0; i < k; ++i) {
    const double t = (r[i] - x[i] + m[i] * h) / r[i];
    if (t > 0) s += p[i] == 2 ? t * t : std::pow(t, p[i]);
  }
  return s - 1;
}

double hyper_T_slope(const double* x, int k, const double* r, const double* p, const double* m,
                     double h, double* slope) {
  double s = 0, ds = 0;
  for (int i = 0; i < k; ++i) {
    const double t = (r[i] - x[i] + m[i] * h) / r[i];
    if (!(t > 0)) continue;
    const double tp = p[i] == 2 ? t * t : std::pow(t, p[i]);  // hyper_T's bits
    s += tp;
    ds += p[i] * m[i] / r[i] * (p[i] == 2 ? t : tp / t);  // d/dh t^p = p t^(p-1) m/r
  }
  *slope = ds;
  return s - 1;
}

double bt_lower(const double* x, int k, const double* r, const double* m) {
  double h = kInf;
  for (int i = 0; i < k; ++i) h = std::min(h, (x[i] - r[i]) / m[i]);
  return h;
}

double bt_upper(const double* x, int k, const double* m) {
  double h = kInf;
  for (int i = 0; i < k; ++i) h = std::min(h, x[i] / m[i]);
  return h;
}

double bt_hyper(const double* x, int k, const double* r, const double* p, const double* m,
                double* dx, int* iterations) {
  if (iterations) *iterations = 0;
  const double h_hi = bt_upper(x, k, m);
  if (!std::isfinite(h_hi)) {  // some x_i = -inf, or every x_i = +inf
    if (dx) {
      if (h_hi < 0)
        argmin_gradient(x, k, m, dx);
      else
        std::fill(dx, dx + k, 0.0);
    }
    return h_hi;
  }
  double h = h_hi, dT;
  double T = hyper_T_slope(x, k, r, p, m, h_hi, &dT);
  if (T > 0) {  // T(h_hi) <= 0 only where the arg-min term alone is active (non-blending)
    // Newton's method from h_hi (docs/math.md §7.3): T is convex and increasing in h (each term
    // [t]_+^p, p > 1, of a t rising affinely with h), so a step from a point where T > 0 lands
    // between the root and that point: the steps fall monotonely onto the root, quadratically
    // near it (T' > 0 there). [lo, hi] brackets the root; a step that leaves it (rounding past
    // the root, a slope of 0 or NaN) is replaced by the bracket's middle.
    double lo = bt_lower(x, k, r, m), hi = h_hi;
    int it = 0;
    while (it < 200) {
      double next = h - T / dT;
      if (next == h) break;  // the step is below h's rounding: h is the root to rounding
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      ++it;
      const double step = std::abs(next - h);
      h = next;
      T = hyper_T_slope(x, k, r, p, m, h, &dT);
      if (std::abs(T) <= 1e-14 || step <= 1e-14 * std::max(1.0, std::abs(h)) ||
          hi - lo <= 1e-14 * std::max(1.0, std::abs(h)))
        break;
      (T > 0 ? hi : lo) = h;
    }
    if (iterations) *iterations = it;
  }
  if (dx) {
    // §7.5: ∂_i BT = (p_i/r_i) q_i^(p_i-1) / Σ_j (p_j m_j/r_j) q_j^(p_j-1).
    double den = 0;
    for (int i = 0; i < k; ++i) {
      const double q = std::max(0.0, (r[i] - x[i] + m[i] * h) / r[i]);
      dx[i] = p[i] / r[i] * (p[i] == 2 ? q : std::pow(q, p[i] - 1));
      den += m[i] * dx[i];
    }
    if (den > 0 && std::isfinite(den))
      for (int i = 0; i < k; ++i) dx[i] /= den;
    else
      argmin_gradient(x, k, m, dx);
  }
  return h;
}

BtOperator BtOperator::conic(double r1, double r2, double p, std::vector<double> m) {
  BtOperator op;
  op.conic_ = true;
  op.r_ = {r1, r2};
  op.p_ = {p};
  op.m_ = std::move(m);
  return op;
}

BtOperator BtOperator::hyperellipsoid(std::vector<double> r, std::vector<double> p,
                                      std::vector<double> m) {
  BtOperator op;
  op.r_ = std::move(r);
  op.p_ = std::move(p);
  op.m_ = std::move(m);
  return op;
}

double BtOperator::eval(const double* x, const double* r, const double* m, double* dx) const {
  if (conic_) return bt2_conic(x, r[0], r[1], p_[0], m, dx);
  return bt_hyper(x, k(), r, p_.data(), m, dx, nullptr);
}

void BtOperator::range_derivatives(const double* x, const double* r, const double* m, double h,
                                   const double* dx, double* dr) const {
  if (conic_) {
    const ConicParameterDerivatives d = bt2_conic_parameter_derivatives(x, r[0], r[1], p_[0], m);
    dr[0] = d.r1;
    dr[1] = d.r2;
    return;
  }
  for (int i = 0; i < k(); ++i) dr[i] = dx[i] > 0 ? -dx[i] * (x[i] - m[i] * h) / r[i] : 0.0;
}

double BtOperator::value_tolerance(const double* x, double value, const double* r,
                                   const double* m) const {
  return bt_value_tolerance(x, k(), value, r, m);
}

void bulge_weights(double m1, double m2, double G, double cos_theta, double M[2]) {
  const double c = std::max(cos_theta, 0.0);
  if (m1 > m2 * G) {
    M[0] = m1;
    M[1] = c > 0 ? m2 + (m1 / G - m2) * c : m2;
  } else {
    M[0] = c > 0 ? m1 + (m2 * G - m1) * c : m1;
    M[1] = m2;
  }
}

BulgeParameters bulge_parameters(const Vec3& grad_g1, const Vec3& grad_g2, const double r[2],
                                 const double m[2], double omega) {
  BulgeParameters b;
  const double n1 = length(grad_g1), n2 = length(grad_g2);
  double G = 1;
  if (n1 > 0 && n2 > 0 && std::isfinite(n1) && std::isfinite(n2) && n1 / n2 > 0 &&
      std::isfinite(n1 / n2)) {
    b.cos_theta = std::min(1.0, std::max(-1.0, dot(grad_g1, grad_g2) / (n1 * n2)));
    G = n1 / n2;
  }
  for (int i = 0; i < 2; ++i) b.P[i] = r[i] * (1 - b.cos_theta + omega);
  bulge_weights(m[0], m[1], G, b.cos_theta, b.M);
  return b;
}

BulgeBox bulge_box(const BulgeOperand g[2], double radius, const double r[2], const double m[2],
                   double omega) {
  BulgeBox B;
  // |∇n_i| <= |H_i|/|∇g_i| for the unit normal n_i; |∇|∇g_i|| <= |H_i|, and 0 when the bounds
  // pin |∇g_i| to a constant over the box.
  double dn[2], dnorm[2];
  for (int i = 0; i < 2; ++i) {
    dn[i] = g[i].grad_lo > 0 ? iv::up(g[i].hessian / g[i].grad_lo) : kInf;
    dnorm[i] = g[i].grad_lo == g[i].grad_hi ? 0 : g[i].hessian;
  }
  B.dcos = iv::up(dn[0] + dn[1]);  // ∇(n_1·n_2) = J_{n_1}^T n_2 + J_{n_2}^T n_1
  if (std::isfinite(B.dcos)) {
    const BulgeParameters c =
        bulge_parameters(g[0].centre_gradient, g[1].centre_gradient, r, m, omega);
    const double spread = iv::up(B.dcos * radius) + 1e-15;  // + the rounding of cosθ
    B.cos_lo = std::max(-1.0, c.cos_theta - spread);
    B.cos_hi = std::min(1.0, c.cos_theta + spread);
  }
  // G = |∇g_1|/|∇g_2| ∈ [G_lo, G_hi], |∇G| <= |∇|∇g_1||/|∇g_2| + |∇g_1| |∇|∇g_2||/|∇g_2|^2.
  const double G_lo = g[1].grad_hi > 0 ? iv::down(g[0].grad_lo / g[1].grad_hi) : 0;
  const double G_hi = g[1].grad_lo > 0 ? iv::up(g[0].grad_hi / g[1].grad_lo) : kInf;
  const double dG =
      g[1].grad_lo > 0
          ? iv::up(flat_product(dnorm[0], 1 / g[1].grad_lo) +
                   flat_product(g[0].grad_hi * dnorm[1], 1 / (g[1].grad_lo * g[1].grad_lo)))
          : kInf;
  for (int i = 0; i < 2; ++i) {
    B.P_lo[i] = iv::down(r[i] * iv::down(1 - B.cos_hi + omega));
    B.P_hi[i] = iv::up(r[i] * iv::up(1 - B.cos_lo + omega));
  }
  // M_1 = m_1 + (m_2 G - m_1)[cosθ]_+ where m_1 <= m_2 G, else m_1 (M_2 likewise with m_1/G):
  // both pieces agree on m_1 = m_2 G ([BE-4]), so each bound covers both.
  const double c = std::max(0.0, B.cos_hi);
  if (c == 0) {  // [cosθ]_+ = 0 on the whole box: M = m
    for (int i = 0; i < 2; ++i) {
      B.M_hi[i] = m[i];
      B.dM[i] = 0;
    }
    return B;
  }
  const double rise[2] = {std::max(0.0, iv::up(m[1] * G_hi - m[0])),
                          G_lo > 0 ? std::max(0.0, iv::up(m[0] / G_lo - m[1])) : kInf};
  // |∇(m_1/G)| = m_1|∇G|/G^2
  const double dG_over[2] = {flat_product(m[1], dG),
                             G_lo > 0 ? flat_product(m[0] / (G_lo * G_lo), dG) : kInf};
  for (int i = 0; i < 2; ++i) {
    B.M_hi[i] = iv::up(m[i] + flat_product(rise[i], c));
    B.dM[i] = iv::up(flat_product(rise[i], B.dcos) + flat_product(c, dG_over[i]));
  }
  return B;
}

}  // namespace softtrace

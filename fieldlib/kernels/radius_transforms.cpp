#include "kernels/radius_transforms.h"

#include <algorithm>
#include <cmath>

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPad = 1 + 1e-12;  // relative slack over the rounding of closed-form bounds

double log_k(double w) {
  return std::log(2.0) / std::log1p(w);
}  // k = ln2/ln(1+w)

// sup |∂T/∂w| of T_l and T_r: ln2/((1+w) ln(1+w)), decreasing in w (header comment).
double log_w_slope(double w_lo) {
  return std::log(2.0) / ((1 + w_lo) * std::log1p(w_lo)) * kPad;
}

// T_n's branches that [d] × [w] reaches: the linear one and the quadratic one.
bool n_linear(Interval d, Interval w) {
  return d.hi >= 0.5 && d.lo < 0.5 * (1 + w.hi);
}
bool n_quadratic(Interval d, double w2hi) {
  return d.lo < 0.5 && d.hi >= 0.5 * (1 - w2hi);
}
// Where T_r is neither 0 nor 1.
bool r_branch(Interval d, Interval w) {
  return d.hi >= 0.5 * (1 - w.hi) && d.lo < 1;
}

}  // namespace

double transform_n(double d, double w1, double w2, TPartials* dT) {
  d = std::max(d, 0.0);
  TPartials p;
  double T;
  if (d >= 0.5 * (1 + w1)) {
    T = 1;
  } else if (d >= 0.5) {
    const double t = d - 0.5;
    T = t / w1 + 0.5;
    p = {1 / w1, -t / (w1 * w1), 0};
  } else if (d >= 0.5 * (1 - w2)) {
    const double t = d - 0.5, A = 2 * (1 / w1 - 1 / w2) / w2;
    T = 0.5 + t / w1 + A * t * t;  // the compact form of N_n
    p = {1 / w1 + 2 * A * t, -t / (w1 * w1) - 2 / (w1 * w1 * w2) * t * t,
         (4 / (w2 * w2 * w2) - 2 / (w1 * w2 * w2)) * t * t};
  } else {
    T = 0;
  }
  if (dT) *dT = p;
  return T;
}

double transform_l(double d, double w1, TPartials* dT) {
  d = std::max(d, 0.0);
  TPartials p;
  double T;
  if (d >= 0.5 * (1 + w1)) {
    T = 1;
  } else if (d == 0) {
    T = 0;  // T_l(0) = 0; its slope there is 0 (k > 1) or unbounded (k <= 1, [TL-3])
  } else {
    const double L = std::log1p(w1), k = std::log(2.0) / L;
    T = std::pow(2 * d / (1 + w1), k);
    p = {k * T / d, -k * T * std::log(2 * d) / ((1 + w1) * L), 0};
  }
  if (dT) *dT = p;
  return T;
}

double transform_r(double d, double w2, TPartials* dT) {
  d = std::max(d, 0.0);
  TPartials p;
  double T;
  if (d >= 1) {
    T = 1;  // A3
  } else if (d < 0.5 * (1 - w2)) {
    T = 0;
  } else {
    const double u = 1 - d, L = std::log1p(w2), k = std::log(2.0) / L;
    const double Y = std::pow(2 * u / (1 + w2), k);
    T = 1 - Y;
    p = {k * Y / u, 0, Y * k * std::log(2 * u) / ((1 + w2) * L)};
  }
  if (dT) *dT = p;
  return T;
}

Interval RadiusProfile::image(Interval d, Interval w) const {
  double lo = eval(d.lo, d.lo >= 0.5 ? w.hi : w.lo, nullptr, nullptr);
  double hi = eval(d.hi, d.hi <= 0.5 ? w.hi : w.lo, nullptr, nullptr);
  // Exact 0 and 1 come from the constant branches and stay exact (flatness is read from them).
  if (lo > 0) lo = std::max(0.0, lo - 1e-13);
  if (hi < 1) hi = std::min(1.0, hi + 1e-13);
  return {lo, hi};
}

void RadiusProfile::store(double* c) const {
  c[0] = static_cast<double>(kind_);
  c[1] = static_cast<double>(rule_);
  c[2] = w2_;
}
RadiusProfile RadiusProfile::load(const double* c) {
  return {static_cast<Kind>(static_cast<int>(c[0])), static_cast<W2Rule>(static_cast<int>(c[1])),
          c[2]};
}

double RadiusProfile::eval(double d, double w, double* Td, double* Tw) const {
  TPartials p;
  double T;
  switch (kind_) {
    case Kind::N:  // T_n(d; w1 = w, w2 = rule(w)), docs/math.md §4.2, §4.5, §4.6
      T = transform_n(d, w, w2(w), &p);
      if (Tw) *Tw = p.w1 + dw2(w) * p.w2;
      break;
    case Kind::L:  // T_l(d; w1 = w), §4.3, §4.5
      T = transform_l(d, w, &p);
      if (Tw) *Tw = p.w1;
      break;
    default:  // T_r(d; w2 = w), §4.4, §4.6
      T = transform_r(d, w, &p);
      if (Tw) *Tw = p.w2;
      break;
  }
  if (Td) *Td = p.d;
  return T;
}

double RadiusProfile::slope_d(Interval d, Interval w) const {
  switch (kind_) {
    case Kind::N:
      return slope_d_n(d, w);
    case Kind::L:
      return slope_d_l(d, w);
    default:
      return slope_d_r(d, w);
  }
}

double RadiusProfile::slope_d_min(Interval d, Interval w) const {
  if (kind_ != Kind::N || !(w.lo > 0)) return 0;
  // The flat branches, with a relative margin for the rounding of their ends: T = 1 from
  // d = 0.5(1 + w1), T = 0 below d = 0.5(1 - w2), w2 = w2(w1) non-decreasing.
  const double margin = 1e-12;
  if (d.hi * (1 + margin) >= 0.5 * (1 + w.lo) * (1 - margin)) return 0;
  const double w2lo = w2(w.lo);
  if (d.lo * (1 - margin) <= 0.5 * (1 - w2(w.hi)) * (1 + margin)) return 0;
  if (rule_ == W2Rule::Fixed && !(w2_ <= 2 * w.lo)) return 0;  // 2/w2 >= 1/w1 needs w2 <= 2 w1
  double s = kInf;
  if (d.hi >= 0.5) s = 1 / w.hi;  // the linear branch
  if (d.lo < 0.5) {               // the quadratic one: at least (1 - τ_hi)/w1_hi
    const double tau = std::min(1.0, (1 - 2 * d.lo) / w2lo * (1 + margin));
    s = std::min(s, (1 - tau) / w.hi);
  }
  return s * (1 - margin);
}

double RadiusProfile::slope_w(Interval d, Interval w) const {
  switch (kind_) {
    case Kind::N:
      return slope_w_n(d, w);
    case Kind::L:
      return d.lo >= 0.5 * (1 + w.hi) ? 0 : log_w_slope(w.lo);
    default:
      return r_branch(d, w) ? log_w_slope(w.lo) : 0;
  }
}

double RadiusProfile::slope_w_per_d(Interval d, Interval w) const {
  return kind_ == Kind::N ? slope_w_per_d_n(d, w) : kInf;
}

double RadiusProfile::w2(double w) const {
  switch (rule_) {
    case W2Rule::Fixed:
      return w2_;
    case W2Rule::Double:
      return std::min(1.0, 2 * w);
    case W2Rule::Equal:
      return w;
  }
  return w2_;
}

double RadiusProfile::dw2(double w) const {
  switch (rule_) {
    case W2Rule::Fixed:
      return 0;
    case W2Rule::Double:
      return 2 * w < 1 ? 2 : 0;
    case W2Rule::Equal:
      return 1;
  }
  return 0;
}

RadiusProfile::Lows RadiusProfile::quadratic_w(Interval d, Interval w) const {
  const double w2lo = std::max(w2(w.lo), 1 - 2 * d.hi);
  switch (rule_) {
    case W2Rule::Fixed:
      return {w.lo, w2lo};
    case W2Rule::Double:
      return {std::max(w.lo, 0.5 * w2lo), w2lo};
    case W2Rule::Equal:
      return {std::max(w.lo, w2lo), w2lo};
  }
  return {w.lo, w2lo};
}

double RadiusProfile::slope_d_n(Interval d, Interval w) const {
  const double w2lo = w2(w.lo), w2hi = w2(w.hi);
  double s = 0;
  if (n_linear(d, w)) s = 1 / w.lo;
  if (n_quadratic(d, w2hi)) {
    const Lows wq = quadratic_w(d, w);
    if (w.lo == w.hi) {  // N_n' is linear in d: its maximum is at an end of the clipped [d]
      const double A = 2 * (1 / w.lo - 1 / w2lo) / w2lo;
      const double a = std::max(d.lo, 0.5 * (1 - w2lo)), b = std::min(d.hi, 0.5);
      s = std::max({s, 1 / w.lo + 2 * A * (a - 0.5), 1 / w.lo + 2 * A * (b - 0.5)});
    } else {
      s = std::max({s, 1 / wq.w1, 2 / wq.w2 - 1 / w.hi});
    }
  }
  return s * kPad;
}

double RadiusProfile::slope_w_n(Interval d, Interval w) const {
  double s = 0;
  if (n_linear(d, w))
    s = std::min((std::min(d.hi, 0.5 * (1 + w.hi)) - 0.5) / (w.lo * w.lo), 0.5 / w.lo);
  const double w2hi = w2(w.hi);
  if (n_quadratic(d, w2hi)) {
    const double e = std::min(0.5 - d.lo, 0.5 * w2hi), w1lo = quadratic_w(d, w).w1;
    // e(1 - 2e/w2) <= min(e, w2/8) and w2 <= 2 w1 for every rule: <= min(e/w1^2, 1/(4 w1)).
    double q = std::min({e, w2hi / 8}) / (w1lo * w1lo);
    q = std::min(q, 0.25 / w1lo);
    if (rule_ == W2Rule::Equal) q += std::min(e / (w1lo * w1lo), 0.5 / w1lo);
    s = std::max(s, q);
  }
  return s * kPad;
}

double RadiusProfile::slope_w_per_d_n(Interval d, Interval w) const {
  if (rule_ == W2Rule::Equal) return kInf;
  double s = 0;
  if (n_linear(d, w))
    s = 2 * std::min((std::min(d.hi, 0.5 * (1 + w.hi)) - 0.5) / (w.lo * w.lo), 0.5 / w.lo);
  if (n_quadratic(d, w2(w.hi))) s = std::max(s, 1 / std::pow(quadratic_w(d, w).w1, 2));
  return s * kPad;
}

double RadiusProfile::slope_d_l(Interval d, Interval w) const {
  if (d.lo >= 0.5 * (1 + w.hi)) return 0;
  const double k = log_k(w.lo);  // the largest k
  double s = 0;
  if (d.hi >= 0.5) s = k / std::max(0.5, d.lo);
  if (d.lo < 0.5) {
    if (w.hi <= 1) {
      s = std::max(s, 2 * k);
    } else {
      if (d.lo <= 0) return kInf;
      s = std::max(s, k * transform_l(std::min(d.hi, 0.5), w.hi, nullptr) / d.lo);
    }
  }
  return s * kPad;
}

double RadiusProfile::slope_d_r(Interval d, Interval w) const {
  if (!r_branch(d, w)) return 0;
  if (w.lo == w.hi) {  // k (2m)^k u^(k-1) grows with u = 1-d (k >= 1)
    const double k = log_k(w.lo), u = std::min(1 - d.lo, 0.5 * (1 + w.lo));
    // In logs: (2m)^k overflows for small w while u^(k-1) underflows.
    return std::exp(std::log(k) + k * std::log(2 / (1 + w.lo)) + (k - 1) * std::log(u)) * kPad;
  }
  return 2 * log_k(w.lo) / (1 + w.lo) * kPad;
}

RadiusProfile make_profile_n(W2Rule rule, double fixed_w2) {
  return {RadiusProfile::Kind::N, rule, fixed_w2};
}
RadiusProfile make_profile_l() {
  return {RadiusProfile::Kind::L, W2Rule::Fixed, 1};
}
RadiusProfile make_profile_r() {
  return {RadiusProfile::Kind::R, W2Rule::Fixed, 1};
}

}  // namespace softtrace

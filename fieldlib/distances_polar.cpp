// Distances in cylindrical coordinates (ρ, φ, z) about the z axis: the torus (circle skeleton)
// and the polar prism whose cross-section radius R(φ) is docs/math.md §10.1's rose or star.
#include <cmath>
#include <limits>

#include "distance_params.h"
#include "distances.h"
#include "gauge.h"
#include "node_util.h"
#include "one_sided.h"
#include "program.h"
#include "skeletal.h"

namespace softtrace {

namespace {

// ((|ρ - R|/a)^n + (|z|/b)^n)^(1/n)   — docs/scene-format.md torus: the LP gauge of §2.5 in the (ρ,
// z) plane, ray-linear about the nearest point of the circle skeleton (docs/math.md §2.1). Bounds:
// |∇ρ| = 1 and ∇ρ ⟂ z, so ∇f has orthogonal parts ∂_1/a and ∂_2/b: the 2-D gauge's
// gauge_lipschitz(1/a, 1/b) globally, partial bounds from (ρ, z) intervals over a box. The
// kernels: skeletal.h.
class Torus final : public FieldNode {
 public:
  Torus(double R, double a, double b, double n) : m_{R, a, b, n, 0} {
    const double w[2] = {1 / a, 1 / b};
    m_.global_L = gauge_lipschitz(w, 2, n);
  }

  double eval(const Vec3& p, Vec3* grad) const override { return torus(m_, p, grad); }
  Interval interval(const Box& b) const override {
    Interval f;
    torus_bounds(m_, b, &f, nullptr);
    return f;
  }
  double lipschitz() const override { return m_.global_L; }
  double lipschitz(const Box& b) const override {
    Interval f;
    double L;
    torus_bounds(m_, b, &f, &L);
    return L;
  }
  // f <= c forces |ρ - R| <= c·a and |z| <= c·b (a power sum is at least its largest term).
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    const double r = (m_.R + level * m_.a) * (1 + 1e-12), h = level * m_.b * (1 + 1e-12);
    return {{-r, -r, -h}, {r, r, h}};
  }
  // One instruction with the parameters inline, in torus_params' order.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{Op::Torus};
    i.in = reg;
    i.out = b.new_slot();
    i.a = b.consts({m_.R, m_.a, m_.b, m_.n, m_.global_L});
    return b.emit(i);
  }

 private:
  TorusParams m_;
};

// The angular profile g(θ) ∈ [-1, 1] of R(φ) = r0 (1 + A g(kφ)): cos θ (rose) or the triangle
// wave (2/π) asin(cos θ) = 1 - 2|θ|/π for θ wrapped to [-π, π] (star). Both have their maxima at
// θ ∈ 2πZ, minima at θ ∈ π + 2πZ, and are monotone in between. |g'| <= 1 and 2/π respectively.
enum class Profile { Cosine, Triangle };

double profile(Profile kind, double theta, double* dg) {
  if (kind == Profile::Cosine) {
    if (dg) *dg = -std::sin(theta);
    return std::cos(theta);
  }
  const double w = std::remainder(theta, 2 * M_PI);
  if (dg) *dg = -2 / M_PI * sgn(w);
  return 1 - 2 * std::abs(w) / M_PI;
}

// (h^n + |z/c|^n)^(1/n), h = ρ/R(φ)   — docs/math.md §10.1's substitutes for [000] Fig. 13's rose
// bar and star contour; ray-linear about the origin. Bounds: in polar coordinates ∇h = e_ρ/R -
// (R'(φ)/R²) e_φ (∂h/∂φ / ρ, ρ cancels), so |∇h|² = (R² + R'²)/R⁴; h is continuous and piecewise
// smooth (the star's kinks), so the largest |∇h| over the R range a box reaches bounds its slope
// there. ∇h ⟂ z, so the outer gauge composes as for the superquadric (gauge_lipschitz / partial
// bounds).
// - star: |R'| = r0 A k (2/π) everywhere, so |∇h|² = 1/R² + R'²/R⁴ is largest at the smallest R.
// - rose: with q = R/r0 = 1 + A cos θ, R'² = r0² k² (A² - (q-1)²), and with s = 1/q
//   r0² |∇h|² = P(s) = (1-k²) s² + 2k² s³ + k² (A²-1) s⁴, a quartic maximised over the s range at
//   its ends or where P'(s)/(2s) = (1-k²) + 3k² s + 2k² (A²-1) s² vanishes.
// Over a box whose (x, y) rectangle misses the axis, the φ range comes from the corners (the
// span is below π), which gives R's range; elsewhere R ∈ [r0 (1-A), r0 (1+A)].
class PolarPrism final : public FieldNode {
 public:
  PolarPrism(double r0, int k, double A, Profile kind, double c, double n)
      : r0_(r0), k_(k), A_(A), kind_(kind), c_(c), n_(n) {
    dR_max_ = r0_ * A_ * k_ * (kind_ == Profile::Cosine ? 1.0 : 2 / M_PI);
    const double wm[2] = {h_slope({r0_ * (1 - A_), r0_ * (1 + A_)}), 1 / c_};
    global_L_ = gauge_lipschitz(wm, 2, n_);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const double rho = std::hypot(p.x, p.y);
    double dg = 0;
    const double R =
        r0_ * (1 + A_ * profile(kind_, k_ * std::atan2(p.y, p.x), grad ? &dg : nullptr));
    const double u[2] = {rho / R, std::abs(p.z) / c_};
    double d[2];
    const double f = power_sum(u, 2, n_, grad ? d : nullptr);
    if (grad) {
      Vec3 gh;
      if (rho > 0) {
        const double dR = r0_ * A_ * k_ * dg;  // R'(φ)
        const Vec3 e_rho{p.x / rho, p.y / rho, 0}, e_phi{-p.y / rho, p.x / rho, 0};
        gh = e_rho / R - e_phi * (dR / (R * R));
      }
      *grad = gh * d[0];
      grad->z = d[1] * sgn(p.z) / c_;
    }
    return f;
  }
  Interval interval(const Box& b) const override {
    Interval u[2];
    return terms(b, u);
  }
  double lipschitz() const override { return global_L_; }
  double lipschitz(const Box& b) const override {
    Interval u[2];
    const Interval f = terms(b, u);
    const double g1 = power_sum_partial_bound(u[0], f, n_) * h_slope(radius_range(b));
    const double g2 = power_sum_partial_bound(u[1], f, n_) / c_;
    const double L = std::sqrt(g1 * g1 + g2 * g2) * (1 + 1e-13);
    return std::isnan(L) ? global_L_ : std::min(global_L_, L);
  }
  // f <= c forces h <= c, so ρ <= c·Rmax = c·r0 (1 + A), and |z| <= c·c_z.
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    const double r = level * r0_ * (1 + A_) * (1 + 1e-12), h = level * c_ * (1 + 1e-12);
    return {{-r, -r, -h}, {r, r, h}};
  }

 private:
  // The largest |∇h| for R ∈ R_range (see the class comment).
  double h_slope(Interval R_range) const {
    const double R_lo = R_range.lo;
    if (kind_ == Profile::Triangle || A_ == 0)
      return std::sqrt(1 / (R_lo * R_lo) + std::pow(dR_max_ / (R_lo * R_lo), 2)) * (1 + 1e-13);
    const double k2 = double(k_) * k_, c4 = k2 * (A_ * A_ - 1);
    const double s_lo = r0_ / R_range.hi, s_hi = r0_ / R_lo;
    double best = 0;
    auto consider = [&](double s) {
      if (!(s >= s_lo && s <= s_hi)) return;
      const double s2 = s * s;
      const double P = (1 - k2) * s2 + 2 * k2 * s2 * s + c4 * s2 * s2;
      const double M = std::abs(1 - k2) * s2 + 2 * k2 * s2 * s + std::abs(c4) * s2 * s2;
      best = std::max(best, P + 1e-12 * M);  // M bounds the terms, so covers their rounding
    };
    consider(s_lo);
    consider(s_hi);
    // Roots of 2 c4 s² + 3 k² s + (1 - k²) = 0 (c4 < 0 since A < 1).
    const double disc = 9 * k2 * k2 - 8 * c4 * (1 - k2);
    if (disc >= 0) {
      const double r = std::sqrt(disc);
      consider((-3 * k2 + r) / (4 * c4));
      consider((-3 * k2 - r) / (4 * c4));
    }
    return std::sqrt(best) / r0_ * (1 + 1e-12);
  }
  // R(φ) over the box: [Rmin, Rmax] unless the rectangle misses the axis.
  Interval radius_range(const Box& b) const {
    Interval g(-1, 1);
    const bool misses_axis = b.lo.x > 0 || b.hi.x < 0 || b.lo.y > 0 || b.hi.y < 0;
    if (misses_axis && b.bounded()) {
      const Vec3 c = b.center();
      const double phi_c = std::atan2(c.y, c.x);
      double lo = 0, hi = 0;
      for (int i = 0; i < 4; ++i) {
        const double x = (i & 1) ? b.hi.x : b.lo.x, y = (i & 2) ? b.hi.y : b.lo.y;
        const double d = std::remainder(std::atan2(y, x) - phi_c, 2 * M_PI);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
      const double pad = 1e-12 * (1 + std::abs(phi_c));  // atan2 and the subtraction's rounding
      g = profile_range(k_ * (phi_c + lo - pad), k_ * (phi_c + hi + pad));
    }
    return {iv::down(r0_ * (1 + A_ * g.lo) * (1 - 1e-15)),
            iv::up(r0_ * (1 + A_ * g.hi) * (1 + 1e-15))};
  }
  // The image of g over [t0, t1]: the end values, plus 1 or -1 where a maximum or minimum lies
  // inside; widened by 1e-12 for the evaluation's rounding.
  Interval profile_range(double t0, double t1) const {
    if (t1 - t0 >= 2 * M_PI) return {-1, 1};
    const double g0 = profile(kind_, t0, nullptr), g1 = profile(kind_, t1, nullptr);
    double lo = std::min(g0, g1), hi = std::max(g0, g1);
    if (std::ceil(t0 / (2 * M_PI)) * 2 * M_PI <= t1) hi = 1;
    if (std::ceil((t0 - M_PI) / (2 * M_PI)) * 2 * M_PI + M_PI <= t1) lo = -1;
    return {std::max(-1.0, lo - 1e-12), std::min(1.0, hi + 1e-12)};
  }
  Interval terms(const Box& b, Interval* u) const {
    u[0] = rho_range(b) / radius_range(b);
    u[1] = abs(b.axis(2)) / Interval(c_);
    return power_sum(u, 2, n_);
  }

  double r0_;
  int k_;
  double A_;
  Profile kind_;
  double c_, n_, dR_max_, global_L_;
};

}  // namespace

NodePtr create_torus(const Params& p, const BuildContext&) {
  const std::vector<double> r = p.numbers("radii");  // [a, b]
  return std::make_unique<Torus>(p.number("major_radius"), r[0], r[1], p.number("n", 2));
}

NodePtr create_polar_prism(const Params& p, const BuildContext&) {
  const double r0 = p.number("radius");
  const int k = p.integer("lobes", 1, 1000);
  const double A = p.number("amplitude");  // 0 <= A < 1 (the table): R(φ) > 0
  const std::string name = p.string("profile");
  const Profile kind = name == "cosine" ? Profile::Cosine : Profile::Triangle;
  return std::make_unique<PolarPrism>(r0, k, A, kind, p.number("half_height"), p.number("n", 20));
}

}  // namespace softtrace

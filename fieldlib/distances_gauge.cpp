// LP metric and superquadric (MATH.md §2.5, §2.6).
#include <cmath>

#include "distances.h"
#include "gauge.h"

namespace softtrace {

namespace {

double sgn(double v) {
  return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
}

Box scaled_box(const Vec3& half, double c) {
  if (c < 0) return Box();
  return {half * -c, half * c};
}

// (|x/a|^n + |y/b|^n + |z/c|^n)^(1/n)   — 000 Eq. 2
class LpMetric final : public FieldNode {
 public:
  LpMetric(const Vec3& radii, double n) : a_(radii), n_(n) {
    const double w[3] = {1 / a_.x, 1 / a_.y, 1 / a_.z};
    global_L_ = gauge_lipschitz(w, 3, n_);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const double u[3] = {std::abs(p.x / a_.x), std::abs(p.y / a_.y), std::abs(p.z / a_.z)};
    double du[3];
    const double f = power_sum(u, 3, n_, grad ? du : nullptr);
    if (grad) *grad = {du[0] * sgn(p.x) / a_.x, du[1] * sgn(p.y) / a_.y, du[2] * sgn(p.z) / a_.z};
    return f;
  }
  Interval interval(const Box& b) const override {
    Interval u[3];
    terms(b, u);
    return power_sum(u, 3, n_);
  }
  double lipschitz() const override { return global_L_; }
  double lipschitz(const Box& b) const override {
    Interval u[3];
    terms(b, u);
    const Interval f = power_sum(u, 3, n_);
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      const double g = power_sum_partial_bound(u[i], f, n_) / a_[i];
      s += g * g;
    }
    return std::min(global_L_, std::sqrt(s) * (1 + 1e-13));
  }
  Box region(double level, Side side) const override {
    return side == Side::Below ? scaled_box(a_, level) : Box::unbounded();
  }

 private:
  void terms(const Box& b, Interval* u) const {
    for (int i = 0; i < 3; ++i) u[i] = abs(b.axis(i)) / Interval(a_[i]);
  }
  Vec3 a_;
  double n_, global_L_;
};

// (( |x/a1|^n1 + |y/a2|^n1 )^(n2/n1) + |z/a3|^n2)^(1/n2)   — 000 Eq. 3 (n1 on both x and y, R2)
class Superquadric final : public FieldNode {
 public:
  Superquadric(const Vec3& radii, double n1, double n2) : a_(radii), n1_(n1), n2_(n2) {
    const double wh[2] = {1 / a_.x, 1 / a_.y};
    const double Lh = gauge_lipschitz(wh, 2, n1_);
    const double wm[2] = {Lh, 1 / a_.z};
    global_L_ = std::isfinite(Lh) ? gauge_lipschitz(wm, 2, n2_) : Lh;
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const double uh[2] = {std::abs(p.x / a_.x), std::abs(p.y / a_.y)};
    double dh[2], dm[2];
    const double h = power_sum(uh, 2, n1_, grad ? dh : nullptr);
    const double um[2] = {h, std::abs(p.z / a_.z)};
    const double f = power_sum(um, 2, n2_, grad ? dm : nullptr);
    if (grad)
      *grad = {dm[0] * dh[0] * sgn(p.x) / a_.x, dm[0] * dh[1] * sgn(p.y) / a_.y,
               dm[1] * sgn(p.z) / a_.z};
    return f;
  }
  Interval interval(const Box& b) const override {
    Interval uh[2], um[2];
    return terms(b, uh, um);
  }
  double lipschitz() const override { return global_L_; }
  double lipschitz(const Box& b) const override {
    Interval uh[2], um[2];
    const Interval f = terms(b, uh, um);
    const double bx = power_sum_partial_bound(uh[0], um[0], n1_) / a_.x;
    const double by = power_sum_partial_bound(uh[1], um[0], n1_) / a_.y;
    const double Lh = std::sqrt(bx * bx + by * by);
    const double gh = power_sum_partial_bound(um[0], f, n2_) * Lh;
    const double gz = power_sum_partial_bound(um[1], f, n2_) / a_.z;
    const double L = std::sqrt(gh * gh + gz * gz) * (1 + 1e-13);
    return std::isnan(L) ? std::numeric_limits<double>::infinity() : std::min(global_L_, L);
  }
  Box region(double level, Side side) const override {
    return side == Side::Below ? scaled_box(a_, level) : Box::unbounded();
  }

 private:
  Interval terms(const Box& b, Interval* uh, Interval* um) const {
    uh[0] = abs(b.axis(0)) / Interval(a_.x);
    uh[1] = abs(b.axis(1)) / Interval(a_.y);
    um[0] = power_sum(uh, 2, n1_);
    um[1] = abs(b.axis(2)) / Interval(a_.z);
    return power_sum(um, 2, n2_);
  }
  Vec3 a_;
  double n1_, n2_, global_L_;
};

Vec3 positive_radii(const Params& p, const std::string& key) {
  const Vec3 r = p.vec3(key);
  for (int i = 0; i < 3; ++i)
    p.check(r[i] > 0, key + "/" + std::to_string(i), "expected a radius > 0");
  return r;
}

}  // namespace

NodePtr create_lp_metric(const Params& p, const BuildContext&) {
  return std::make_unique<LpMetric>(positive_radii(p, "radii"), p.positive("n"));
}

NodePtr create_superquadric(const Params& p, const BuildContext&) {
  return std::make_unique<Superquadric>(positive_radii(p, "radii"), p.positive("n1"),
                                        p.positive("n2"));
}

}  // namespace softtrace

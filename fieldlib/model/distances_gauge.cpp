// LP metric, superquadric and super-elliptic cylinder, with the optional six side lengths
// (docs/math.md §2.5, §2.6, §2.9, §2.10).
#include <algorithm>
#include <cmath>
#include <limits>

#include "describe/distance_params.h"
#include "kernels/gauge.h"
#include "kernels/lp_metric.h"
#include "kernels/one_sided.h"
#include "kernels/spherical_product.h"
#include "math/bound_util.h"
#include "model/distances.h"
#include "model/kernel_node.h"
#include "model/program_builder.h"
#include "program/ops/gauge_ops.h"

namespace softtrace {

namespace {

Box scaled_box(const Vec3& half, double c) {
  if (c < 0) return Box();
  return {half * -c, half * c};
}

// (|x/a|^n + |y/b|^n + |z/c|^n)^(1/n)   — 000 Eq. 2
class LpMetric final : public FieldNode {
 public:
  LpMetric(const Vec3& radii, double n) {
    const double w[3] = {1 / radii.x, 1 / radii.y, 1 / radii.z};
    m_ = LpMetricParams::make(radii, n, gauge_lipschitz(w, 3, n));
  }

  double eval(const Vec3& p, Vec3* grad) const override { return lp_metric(m_, p, grad); }
  // With n = 2, |diag(1/a) x|: an ellipsoid's distance.
  bool polynomial_blob(PolynomialBlob* b) const override {
    if (m_.n != 2) return false;
    b->L.r[0] = {m_.ia.x, 0, 0};
    b->L.r[1] = {0, m_.ia.y, 0};
    b->L.r[2] = {0, 0, m_.ia.z};
    b->k = {};
    return true;
  }
  double lipschitz() const override { return m_.global_L; }
  // One instruction with the parameters inline.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.single(Op::LpMetric, reg, LpMetricOp::constants(m_));
  }
  NodePtr clone() const override { return std::make_unique<LpMetric>(*this); }
  Box region(double level, Side side) const override {
    return side == Side::Below ? scaled_box(m_.a, level) : Box::unbounded();
  }
  // For n = 2, f = |Ax| with A = diag(1/a): ∇f = A v with v = Ax/f a unit vector, so
  // |∇f|^2 = Σ w_i/a_i^2 / Σ w_i with w_i = (x_i/a_i)^2 — a linear-fractional function of w,
  // smallest at a corner of w's box — and Hf = A(I - vv^T)A/f, of norm <= max(1/a_i^2)/f.
  double gradient_floor(const Box& b) const override {
    if (m_.n != 2) return 0;
    Interval w[3];
    lp_metric_terms(m_, b, w);
    for (Interval& wi : w) wi = sqr(wi);
    if (w[0].lo + w[1].lo + w[2].lo <= 0) return 0;  // the box may hold the centre
    double g2 = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      double num = 0, den = 0;
      for (int i = 0; i < 3; ++i) {
        const double wi = (corner >> i) & 1 ? w[i].hi : w[i].lo;
        num += wi / (m_.a[i] * m_.a[i]);
        den += wi;
      }
      g2 = std::min(g2, num / den);
    }
    return std::sqrt(g2) * (1 - 1e-12);
  }
  double hessian_bound(const Box& b) const override {
    const double f = m_.n == 2 ? interval(b).lo : 0;
    if (!(f > 0)) return std::numeric_limits<double>::infinity();
    const double amin = std::min({m_.a.x, m_.a.y, m_.a.z});
    return iv::up(1 / iv::down(amin * amin * f));
  }
  bool hessian(const Vec3& p, Mat3* H) const override { return lp_metric_hessian(m_, p, H); }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    NodeBounds out;
    lp_metric_bounds(m_, b, &out.value, &out.lipschitz);
    return out;
  }

  LpMetricParams m_;
};

// m(h(x,y), ζ_L(z)) with h = (u_x^n1 + u_y^n1)^(1/n1), m = (h^n2 + u_z^n2)^(1/n2) and the
// one-sided terms u of one_sided.h. L = 0: the superquadric, 000 Eq. 3 / 002 Eq. 15 (n1 on both x
// and y, R2); n1 = n2, L >= 0: the super-elliptic cylinder, 002 Eqs. 17-18. docs/math.md §2.6,
// §2.9-2.10. The kernels and their bounds: spherical_product.h. The nested gauge_lipschitz with
// the largest slopes 1/(a·min t) is global because ∇h ⟂ z. Its node is
// KernelNode<SphericalProduct>.
struct SphericalProduct {
  using Params = SphericalProductParams;
  using OpKernel = SphericalProductOp;
  static constexpr Op kOp = Op::SphericalProduct;
  static SphericalProductParams params(const OneSidedTerm (&t)[3], double n1, double n2) {
    SphericalProductParams m{{t[0], t[1], t[2]}, n1, n2, 0};
    const double wh[2] = {t[0].slope(), t[1].slope()};
    const double Lh = gauge_lipschitz(wh, 2, n1);
    const double wm[2] = {Lh, t[2].slope()};
    m.global_L = std::isfinite(Lh) ? gauge_lipschitz(wm, 2, n2) : Lh;
    return m;
  }
  static double value(const SphericalProductParams& m, const Vec3& p, Vec3* grad) {
    return spherical_product(m, p, grad);
  }
  // (The kernel's bounds take optional scratch arguments: no KernelOf here.)
  static void bounds(const SphericalProductParams& m, const Box& b, Interval* value,
                     double* lipschitz) {
    spherical_product_bounds(m, b, value, lipschitz);
  }
  static double lipschitz(const SphericalProductParams& m) { return m.global_L; }
  // [DF-5]: a power sum is at least its largest term, so f <= c needs every u <= c.
  static Box region(const SphericalProductParams& m, double level, Side side) {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    Box b;
    for (int i = 0; i < 3; ++i) {
      const Interval s = m.t[i].below(level);
      b.lo[i] = s.lo;
      b.hi[i] = s.hi;
    }
    return b;
  }
};

// Terms for radii a1..a3 and side lengths t1..t6 (t_{2i-1} on +axis i, t_{2i} on -axis i).
NodePtr spherical_product_node(const Params& p, double n1, double n2, double half_length) {
  const Vec3 a = p.vec3("radii");
  const std::vector<double> t = side_lengths(p, "t", 6);
  OneSidedTerm terms[3];
  for (int i = 0; i < 3; ++i) terms[i] = {a[i] * t[2 * i], a[i] * t[2 * i + 1], 0.0};
  terms[2].dead = half_length;
  return std::make_unique<KernelNode<SphericalProduct>>(SphericalProduct::params(terms, n1, n2));
}

}  // namespace

NodePtr create_lp_metric(const Params& p, const BuildContext&) {
  return std::make_unique<LpMetric>(p.vec3("radii"), p.number("n"));
}

NodePtr create_superquadric(const Params& p, const BuildContext&) {
  const double n1 = p.number("n1"), n2 = p.number("n2");
  return spherical_product_node(p, n1, n2, 0.0);
}

NodePtr create_superelliptic_cylinder(const Params& p, const BuildContext&) {
  const double n = p.number("n");
  return spherical_product_node(p, n, n, p.number("half_length"));
}

}  // namespace softtrace

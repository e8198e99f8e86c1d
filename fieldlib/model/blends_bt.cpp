#include "model/blends_bt.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "describe/building.h"
#include "kernels/bt_base.h"
#include "kernels/bt_blend.h"
#include "kernels/bulge_gradient.h"
#include "math/bound_util.h"
#include "math/scratch.h"
#include "model/nary_node.h"
#include "model/program_builder.h"
#include "program/ops/bt_ops.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTiny = std::numeric_limits<double>::denorm_min();

Interval signed_interval(int sigma, Interval a) {
  return sigma > 0 ? a : -a;
}

// R = τ·BT_k(σ_1 f_1, ..., σ_k f_k) — 003 Eqs. 2–5 and §3.3, docs/math.md §7.1–§7.4 (§7.6 with
// bulge)
class BtBlend final : public NaryNode<BtBlend> {
 public:
  BtBlend(std::vector<NodePtr> children, BtOperator op, int tau, std::vector<int> sigma,
          double omega)
      : NaryNode(std::move(children)),
        op_(std::move(op)),
        tau_(tau),
        sigma_(std::move(sigma)),
        omega_(omega),
        consts_(BtCombination::constants(
            op_.is_conic(), tau_, sigma_, op_.r(),
            op_.is_conic() ? std::vector<double>{op_.conic_p(), 0} : op_.p(), op_.m())) {
    for (int i = 0; i < op_.k(); ++i)  // r_i(2 + ω) rounded as P_i is, so P_i <= r_max_[i]
      r_max_.push_back(bulge() ? op_.r()[i] * (2 + omega_) : op_.r()[i]);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const int k = op_.k();
    const bool need_g = grad || bulge();
    Scratch<double> x(k), dx(k);
    Scratch<Vec3> g(k);
    for (int i = 0; i < k; ++i) {
      x[i] = sigma_[i] * c_[i]->eval(p, need_g ? &g[i] : nullptr);
      if (need_g) g[i] = g[i] * sigma_[i];
    }
    double v;
    Vec3 s;  // ∇BT
    if (bulge()) {
      const BulgeParameters b =
          bulge_parameters(g[0], g[1], op_.r().data(), op_.m().data(), omega_);
      v = op_.eval(x.data(), b.P, b.M, grad ? dx.data() : nullptr);
      if (grad) s = position_terms(p, x.data(), g.data(), b, v, dx.data());
    } else {
      v = op_(x.data(), grad ? dx.data() : nullptr);
    }
    if (grad) {
      for (int i = 0; i < k; ++i) s += g[i] * dx[i];
      *grad = s * tau_;
    }
    return tau_ * v;
  }

  double lipschitz() const override {
    if (bulge()) return kInf;
    double L = 0;
    for (int i = 0; i < op_.k(); ++i) L = std::max(L, iv::up(c_[i]->lipschitz() / op_.m()[i]));
    return L;
  }

  // Without bulge elimination: the children's code as a group (never pruned), then one Bt
  // instruction, whose slope along a segment is derived from the children's (bt_blend.h). With
  // it, one oracle instruction (P_i and M_i follow the children's gradients).
  int compile(ProgramBuilder& b, int reg) const override {
    if (bulge()) return FieldNode::compile(b, reg);
    return b.nary(Op::Bt, c_, reg, b.consts(consts_));
  }

  Box region(double level, Side side) const override {
    // R <= c  ⇔  BT <= c (τ = 1) or BT >= -c (τ = -1); R >= c likewise with the sides swapped.
    const bool bt_below = (side == Side::Below) == (tau_ > 0);
    const double c = tau_ > 0 ? level : -level;
    return bt_below ? region_below(c) : region_above(c);
  }

 private:
  friend NaryNode;

  // From the children's intervals I and bounds L over b: BT at the ends of X_i = σ_i [f_i], and the
  // largest L_i/m_i among the children that can be active in the box; with bulge elimination,
  // bulge_bounds.
  NodeBounds combine(const Box& b, const Interval* I, const double* L) const {
    if (!bulge()) {
      NodeBounds nb;
      nb.value = BtCombination::load(consts_.data())
                     .bounds([&](int i) { return I[i]; }, [&](int i) { return L[i]; },
                             [](int) { return Interval(); }, false, &nb.lipschitz, nullptr);
      return nb;
    }
    Slots<double> lo(2), hi(2);  // the ends of X_i = σ_i [f_i]
    for (int i = 0; i < 2; ++i) {
      const Interval X = signed_interval(sigma_[i], I[i]);
      lo.set(i, X.lo);
      hi.set(i, X.hi);
    }
    return bulge_bounds(b, lo.data(), hi.data(), L);
  }

  bool bulge() const { return omega_ > 0; }

  // The true gradient's terms from the position functions (blends_bt.h): Σ_i ∂_{r_i}BT ∇P_i +
  // ∂_{m_i}BT ∇M_i at p, with ∂_{m_i}BT = -h ∂_iBT (§7.5); x, g the operands' values and
  // gradients, b the position functions' values there, h = BT and dx = ∂_iBT.
  Vec3 position_terms(const Vec3& p, const double* x, const Vec3* g, const BulgeParameters& b,
                      double h, const double* dx) const {
    // Outside both terms, or at an infinite value (an infinite child), P and M do not matter.
    if ((dx[0] == 0 && dx[1] == 0) || !std::isfinite(h)) return {};
    Mat3 H[2];
    for (int i = 0; i < 2; ++i) H[i] = operand_hessian(i, p);
    const BulgeGradients d = bulge_gradients(g, H, op_.r().data(), op_.m().data());
    double dr[2];
    op_.range_derivatives(x, b.P, b.M, h, dx, dr);
    Vec3 s;
    for (int i = 0; i < 2; ++i) s += d.P[i] * dr[i] + d.M[i] * (-h * dx[i]);
    return s;
  }

  // The Hessian of the union operand σ_i f_i at p: the child's exact one (FieldNode::hessian)
  // or, where it gives none, central differences of its gradient with the step δ = 1e-5·(1 +
  // max|p_j|) (truncation O(δ²) times the third derivatives, rounding O(ε/δ) of |∇f|: both far
  // below what moves a normal by 0.01 degrees on the scenes' scales), symmetrised.
  Mat3 operand_hessian(int i, const Vec3& p) const {
    Mat3 H;
    if (!c_[i]->hessian(p, &H)) {
      const double delta = 1e-5 * (1 + max_abs(p));
      for (int j = 0; j < 3; ++j) {
        Vec3 a = p, c = p, ga, gc;
        a[j] += delta;
        c[j] -= delta;
        c_[i]->eval(a, &ga);
        c_[i]->eval(c, &gc);
        H.r[j] = (ga - gc) / (a[j] - c[j]);
      }
      for (int j = 0; j < 3; ++j)
        for (int l = j + 1; l < 3; ++l) H.r[j][l] = H.r[l][j] = 0.5 * (H.r[j][l] + H.r[l][j]);
    }
    for (Vec3& row : H.r) row = row * sigma_[i];
    return H;
  }

  // A box containing {σ_i f_i <= t} (below) or {σ_i f_i >= t} (!below).
  Box child_region(int i, double t, bool below) const {
    const bool child_below = below == (sigma_[i] > 0);
    return c_[i]->region(sigma_[i] > 0 ? t : -t, child_below ? Side::Below : Side::Above);
  }
  // {BT <= c} ⊂ ∪_i {x_i <= r_i + m_i c}; with bulge elimination only for c <= 0.
  Box region_below(double c) const {
    if (bulge() && c > 0) return Box::unbounded();
    Box out;
    for (int i = 0; i < op_.k(); ++i)
      out = out.united(child_region(i, iv::up(r_max_[i] + iv::up(op_.m()[i] * c)), true));
    return out;
  }
  // {BT >= c} ⊂ ∩_i {x_i >= m_i c}; with bulge elimination only for c >= 0.
  Box region_above(double c) const {
    if (bulge() && c < 0) return Box::unbounded();
    Box out = Box::unbounded();
    for (int i = 0; i < op_.k(); ++i)
      out = out.intersected(child_region(i, iv::down(op_.m()[i] * c), false));
    return out;
  }

  // With bulge elimination, over b: the enclosure and the bound of blends_bt.h, both from one
  // computation of the position functions' ranges (lo, hi the ends of X_i = σ_i [f_i]; L the
  // children's box bounds).
  NodeBounds bulge_bounds(const Box& b, const double* lo, const double* hi, const double* L) const {
    BulgeOperand g[2];
    const BulgeBox B = position_ranges(b, L, g);
    const Interval bt = bulge_enclosure(lo, hi, B);
    return {tau_ > 0 ? bt : -bt, bulge_lipschitz(lo, hi, g, B, bt)};
  }

  // The position functions' ranges and slopes over the box, from the operands' gradient
  // floors and Hessian bounds (bt_base.h, bulge_box) and their box Lipschitz bounds L; `g`
  // receives the operands' bounds.
  BulgeBox position_ranges(const Box& b, const double* L, BulgeOperand g[2]) const {
    bool known = true;
    for (int i = 0; i < 2; ++i) {
      g[i].grad_lo = c_[i]->gradient_floor(b);
      g[i].grad_hi = L[i];
      g[i].hessian = c_[i]->hessian_bound(b);
      known = known && g[i].grad_lo > 0 && std::isfinite(g[i].hessian);
    }
    if (known)  // the centre anchors cosθ's range; without slope bounds it is [-1, 1] anyway
      for (int i = 0; i < 2; ++i) {
        c_[i]->eval(b.center(), &g[i].centre_gradient);
        g[i].centre_gradient = g[i].centre_gradient * sigma_[i];
      }
    return bulge_box(g, 0.5 * b.diagonal(), op_.r().data(), op_.m().data(), omega_);
  }

  // Where the base is homogeneous in its ranges, BT is non-decreasing in x, non-increasing in
  // the ranges' factor c and monotone in each M_i with the sign of -BT, a sign M cannot change
  // ([BT-1]): its extremes over the box are at corners. Otherwise (or with M unbounded) the
  // bracket min_i (x_i - P_i)/M_i <= BT <= min_i x_i/M_i, of which M_hi = inf keeps the sign only.
  Interval bulge_enclosure(const double* lo, const double* hi, const BulgeBox& B) const {
    const bool corners = homogeneous() && std::isfinite(B.M_hi[0]) && std::isfinite(B.M_hi[1]);
    const Interval v = corners ? bulge_corners(lo, hi, B) : bulge_bracket(lo, hi, B);
    if (std::isnan(v.lo) || std::isnan(v.hi)) return Interval::entire();
    return v;
  }

  Interval bulge_corners(const double* lo, const double* hi, const BulgeBox& B) const {
    const double* m = op_.m().data();
    const auto padded = [&](const double* x, const double* P, const double* M, double side) {
      const double v = op_.eval(x, P, M, nullptr);
      return v + side * 2 * op_.value_tolerance(x, v, P, M);
    };
    return iv::out(std::min(padded(lo, B.P_hi, m, -1), padded(lo, B.P_hi, B.M_hi, -1)),
                   std::max(padded(hi, B.P_lo, m, 1), padded(hi, B.P_lo, B.M_hi, 1)));
  }

  Interval bulge_bracket(const double* lo, const double* hi, const BulgeBox& B) const {
    double L = kInf, U = kInf;
    for (int i = 0; i < op_.k(); ++i) {
      const double m = op_.m()[i], M = B.M_hi[i];
      const double n = iv::down(lo[i] - B.P_hi[i]);  // lower end of x_i - P_i
      const double tn = 1e-9 * (std::abs(lo[i]) + B.P_hi[i]);
      if (n > tn)
        L = std::min(L, std::isfinite(M) ? iv::down((n - tn) / M) : kTiny);
      else
        L = std::min(L, iv::down((n - tn) / m));
      const double th = 1e-9 * (std::abs(hi[i]) + B.P_hi[i]);
      if (hi[i] < -th)
        U = std::min(U, std::isfinite(M) ? iv::up((hi[i] + th) / M) : -kTiny);
      else
        U = std::min(U, iv::up((hi[i] + th) / m));
    }
    return {L, U};
  }

  // The base scales with its ranges: BT(x; c·r) = c·BT(x/c; r) (blends_bt.h).
  bool homogeneous() const { return !op_.is_conic() || op_.conic_p() == 0; }

  // |∇BT| <= max_i L_i/m_i + max_i (r_i/m_i)|∇cosθ| + |BT| max_i |∇M_i|/m_i (blends_bt.h), the
  // first two maxima over the children that can be active in the box; `bt` is BT's enclosure
  // over it, `g` the operands' bounds (their grad_hi the children's box Lipschitz bounds).
  double bulge_lipschitz(const double* lo, const double* hi, const BulgeOperand* g,
                         const BulgeBox& B, Interval bt) const {
    if (!homogeneous()) return kInf;
    double slope = 0, range = 0, weight = 0;
    int active = 0;
    for (int i = 0; i < 2; ++i) {
      const double m = op_.m()[i];
      weight = std::max(weight, iv::up(B.dM[i] / m));
      if (!can_be_active(i, lo, hi, B.P_hi, B.M_hi)) continue;
      ++active;
      slope = std::max(slope, iv::up(g[i].grad_hi / m));
      range = std::max(range, iv::up(op_.r()[i] / m));
    }
    if (active < 2) range = 0;  // one term: BT = x_j/M_j does not depend on the ranges
    const double h = magnitude(bt);
    return iv::up(slope + iv::up(flat_product(range, B.dcos)) + iv::up(flat_product(h, weight)));
  }

  // Whether ∂_iBT can be non-zero in the box (bt_base.h).
  bool can_be_active(int i, const double* lo, const double* hi, const double* P_hi,
                     const double* M_hi) const {
    return bt_can_be_active(i, op_.k(), lo, hi, P_hi, op_.m().data(), M_hi);
  }

  BtOperator op_;
  int tau_;
  std::vector<int> sigma_;
  double omega_;                // 0: no bulge elimination
  std::vector<double> consts_;  // BtCombination's constants (bt_blend.h)
  std::vector<double> r_max_;   // r_i(2 + ω): the largest P_i, for region()
};

enum class BtKind { Union, Intersection, Difference, Displacement };

const char* kind_name(BtKind kind) {
  switch (kind) {
    case BtKind::Union:
      return "bt_union";
    case BtKind::Intersection:
      return "bt_intersection";
    case BtKind::Difference:
      return "bt_difference";
    case BtKind::Displacement:
      return "displacement_union";
  }
  return "";
}

NodePtr create_bt(const Params& p, const BuildContext& ctx, BtKind kind) {
  const std::string name = kind_name(kind);
  p.check(ctx.convention == Convention::Zero, "type",
          name +
              " is defined in the zero convention only (inside f <= 0, docs/math.md §7.4); set the "
              "object's \"convention\" to \"zero\"");
  std::vector<NodePtr> children = build_children(p, "children", ctx);
  const size_t k = children.size();

  std::vector<double> m(k, 1.0);
  if (kind != BtKind::Displacement && p.has("m")) m = p.numbers_or_scalar("m", k);

  const std::string base = p.string("base");  // "conic" or "hyperellipsoid" (the table)
  BtOperator op;
  double conic_p = 0, r1 = 0, r2 = 0;
  if (base == "conic") {
    p.check(k == 2, "children",
            "the conic base blends exactly 2 children (docs/math.md §7.2); use \"hyperellipsoid\" "
            "for more");
    r1 = p.positive("r1");  // required with the conic base: the table cannot say so
    r2 = p.positive("r2");
    conic_p = p.number("p");
    p.check(conic_p < r1 * r2, "p",
            "expected p < r1*r2 (docs/math.md §6.1: p = r1*r2 degenerates to the chord)");
    op = BtOperator::conic(r1, r2, conic_p, m);
  } else {
    std::vector<double> r = p.numbers_or_scalar("r", k), pe = p.numbers_or_scalar("p", k);
    for (double pi : pe)
      p.check(pi > 1, "p", "expected every p_i > 1 (docs/math.md §7.3: T is C^1, its root unique)");
    op = BtOperator::hyperellipsoid(std::move(r), std::move(pe), m);
  }

  double omega = 0;
  if (p.has("bulge_elimination")) {
    const Params be = p.object("bulge_elimination");
    be.check_keys({"omega"});  // a misspelled key before a missing one, as everywhere
    omega = be.positive("omega");
    be.check(omega <= kMaxMagnitude, "omega", "expected a number of magnitude at most 1e150");
    be.finish();
    p.check(k == 2, "bulge_elimination",
            "bulge elimination takes exactly 2 children (003 §5, docs/math.md §7.6)");
    if (op.is_conic())
      p.check(conic_p < omega * omega * r1 * r2, "p",
              "with bulge elimination the ranges shrink to r_i*omega, so a conic base needs "
              "p < omega^2*r1*r2 (docs/math.md §6.1, §7.6)");
  }

  int tau = 1;
  std::vector<int> sigma(k, 1);
  if (kind == BtKind::Intersection) {
    tau = -1;
    std::fill(sigma.begin(), sigma.end(), -1);
  } else if (kind == BtKind::Difference) {
    tau = -1;
    sigma[0] = -1;
  }
  return std::make_unique<BtBlend>(std::move(children), std::move(op), tau, std::move(sigma),
                                   omega);
}

}  // namespace

NodePtr create_bt_union(const Params& p, const BuildContext& ctx) {
  return create_bt(p, ctx, BtKind::Union);
}
NodePtr create_bt_intersection(const Params& p, const BuildContext& ctx) {
  return create_bt(p, ctx, BtKind::Intersection);
}
NodePtr create_bt_difference(const Params& p, const BuildContext& ctx) {
  return create_bt(p, ctx, BtKind::Difference);
}
NodePtr create_displacement_union(const Params& p, const BuildContext& ctx) {
  return create_bt(p, ctx, BtKind::Displacement);
}

}  // namespace softtrace

// Super-ellipsoidal (CG Ricci) union and intersection of distance functions: positively
// homogeneous of degree 1, so ray-linear children give a ray-linear result (002 §4.5 closure,
// docs/math.md §2.1, §5.3). [002] builds modulation and contour surfaces this way.
#include <algorithm>
#include <cmath>
#include <limits>

#include "describe/building.h"
#include "kernels/gauge.h"
#include "kernels/super_ellipsoidal.h"
#include "math/scratch.h"
#include "model/distances.h"
#include "model/nary_node.h"
#include "model/program_builder.h"
#include "program/ops/nary_ops.h"

namespace softtrace {

namespace {

// (Σ x_i^-n)^(-1/n), 0 when some x_i <= 0 (the limit)   — 000 Eq. 6 B_RU^cg, docs/math.md §5.3.
// Partials v_i = (U/x_i)^(n+1) = w_i^(1+1/n) with w_i = (U/x_i)^n, Σ w_i = 1, so Σ v_i <= 1 and
// |∇U| <= Σ v_i L_i <= max_i L_i; over a box v_i <= min(1, (U_hi/x_i,lo)^(n+1)). U is
// non-decreasing in every x_i: the interval is U at the children's lower and upper ends.
// region: U <= min x_i, and U >= min x_i / k^(1/n), so {U <= c} ⊂ ∪ {x_i <= c k^(1/n)} and
// {U >= c} ⊂ ∩ {x_i >= c}.
class SuperEllipsoidalUnion final : public NaryNode<SuperEllipsoidalUnion> {
 public:
  SuperEllipsoidalUnion(std::vector<NodePtr> children, double n)
      : NaryNode(std::move(children)), n_(n) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = c_.size();
    Scratch<double> x(k);
    Scratch<Vec3> g(k);
    for (size_t i = 0; i < k; ++i) x[i] = c_[i]->eval(p, grad ? &g[i] : nullptr);
    const double U = super_union(x.data(), k, n_);
    if (grad) *grad = super_union_gradient(x.data(), g.data(), k, n_, U);
    return U;
  }
  double lipschitz() const override {
    double L = 0;
    for (const auto& c : c_) L = std::max(L, c->lipschitz());
    return L;
  }
  Box region(double level, Side side) const override {
    Box out = side == Side::Below ? Box() : Box::unbounded();
    const double scale = std::pow(static_cast<double>(c_.size()), 1 / n_) * (1 + 1e-13);
    for (const auto& c : c_) {
      if (side == Side::Below)
        out = out.united(c->region(level * scale, side));
      else
        out = out.intersected(c->region(level, side));
    }
    return out;
  }
  // The children's code as a group (never pruned: they are distances, not soft fields), then
  // one instruction with n inline.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.nary(Op::SuperUnion, c_, reg, b.consts(SuperUnionOp::constants(n_)));
  }

 private:
  friend NaryNode;

  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    const size_t k = c_.size();
    const Interval U = super_union_interval(I, k, n_);
    return {U, super_union_lipschitz(I, L, k, n_, U)};
  }

  double n_;
};

// (Σ x_i^n)^(1/n) with x_i clamped at 0   — 000 Eq. 6 B_RI^cg, docs/math.md §5.3.
// Partials (x_i/I)^(n-1) = w_i^((n-1)/n) with Σ w_i = 1 have l_q norm 1 (1/n + 1/q = 1) for
// n >= 1, so |∇I| <= (Σ L_i^n)^(1/n) by Hölder; no global bound for n < 1. Over a box the
// partials come from power_sum_partial_bound. Monotone, so the interval is the power sum of the
// children's intervals. region: I >= max x_i, so {I <= c} ⊂ ∩ {x_i <= c}; I <= k^(1/n) max x_i,
// so {I >= c} ⊂ ∪ {x_i >= c / k^(1/n)}.
class SuperEllipsoidalIntersection final : public NaryNode<SuperEllipsoidalIntersection> {
 public:
  SuperEllipsoidalIntersection(std::vector<NodePtr> children, double n)
      : NaryNode(std::move(children)), n_(n) {
    global_L_ = std::numeric_limits<double>::infinity();
    if (n_ < 1) return;
    std::vector<double> L;
    for (const auto& c : c_) L.push_back(c->lipschitz());
    // A child without a bound leaves none (the power sum would give inf/inf = NaN).
    if (std::any_of(L.begin(), L.end(), [](double l) { return std::isinf(l); })) return;
    global_L_ = power_sum(L.data(), static_cast<int>(L.size()), n_, nullptr) * (1 + 1e-13);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = c_.size();
    Scratch<double> x(k);
    Scratch<Vec3> g(k);
    for (size_t i = 0; i < k; ++i) x[i] = c_[i]->eval(p, grad ? &g[i] : nullptr);
    return super_intersection(x.data(), g.data(), k, n_, grad);
  }
  double lipschitz() const override { return global_L_; }
  Box region(double level, Side side) const override {
    Box out = side == Side::Below ? Box::unbounded() : Box();
    const double scale = std::pow(static_cast<double>(c_.size()), 1 / n_) * (1 + 1e-13);
    for (const auto& c : c_) {
      if (side == Side::Below)
        out = out.intersected(c->region(level, side));
      else
        out = out.united(c->region(level / scale, side));
    }
    return out;
  }
  // As the union's: a group never pruned, then one instruction with n and the global bound.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.nary(Op::SuperIntersect, c_, reg,
                  b.consts(SuperIntersectOp::constants(n_, global_L_)));
  }

 private:
  friend NaryNode;

  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    const size_t k = c_.size();
    const Interval f = power_sum(I, static_cast<int>(k), n_);
    return {f, super_intersection_lipschitz(I, L, k, n_, f, global_L_)};
  }

  double n_, global_L_;
};

}  // namespace

NodePtr create_super_ellipsoidal_union(const Params& p, const BuildContext& ctx) {
  const double n = p.number("n");
  return std::make_unique<SuperEllipsoidalUnion>(build_children(p, "children", ctx), n);
}

NodePtr create_super_ellipsoidal_intersection(const Params& p, const BuildContext& ctx) {
  const double n = p.number("n");
  return std::make_unique<SuperEllipsoidalIntersection>(build_children(p, "children", ctx), n);
}

}  // namespace softtrace

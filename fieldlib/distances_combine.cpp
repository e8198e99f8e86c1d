// Super-ellipsoidal (CG Ricci) union and intersection of distance functions: positively
// homogeneous of degree 1, so ray-linear children give a ray-linear result (002 §4.5 closure,
// docs/math.md §2.1, §5.3). [002] builds modulation and contour surfaces this way.
#include <algorithm>
#include <cmath>
#include <limits>

#include "distances.h"
#include "gauge.h"
#include "one_sided.h"
#include "registry.h"
#include "scratch.h"

namespace softtrace {

namespace {

// (Σ x_i^-n)^(-1/n), 0 when some x_i <= 0 (the limit)   — 000 Eq. 6 B_RU^cg, docs/math.md §5.3.
// Partials v_i = (U/x_i)^(n+1) = w_i^(1+1/n) with w_i = (U/x_i)^n, Σ w_i = 1, so Σ v_i <= 1 and
// |∇U| <= Σ v_i L_i <= max_i L_i; over a box v_i <= min(1, (U_hi/x_i,lo)^(n+1)). U is
// non-decreasing in every x_i: the interval is U at the children's lower and upper ends.
// region: U <= min x_i, and U >= min x_i / k^(1/n), so {U <= c} ⊂ ∪ {x_i <= c k^(1/n)} and
// {U >= c} ⊂ ∩ {x_i >= c}.
class SuperEllipsoidalUnion final : public FieldNode {
 public:
  SuperEllipsoidalUnion(std::vector<NodePtr> children, double n) : c_(std::move(children)), n_(n) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = c_.size();
    Scratch<double> x(k);
    Scratch<Vec3> g(k);
    for (size_t i = 0; i < k; ++i) x[i] = c_[i]->eval(p, grad ? &g[i] : nullptr);
    const double U = combine(x.data());
    if (grad) {
      *grad = {};
      if (U == 0) {
        // U = x_j on the zero set of child j (the partial (U/x_j)^(n+1) tends to 1 there).
        for (size_t i = 0; i < k; ++i)
          if (x[i] <= 0) {
            *grad = x[i] == 0 ? g[i] : Vec3{};
            break;
          }
      } else {
        for (size_t i = 0; i < k; ++i) *grad += g[i] * std::pow(U / x[i], n_ + 1);
      }
    }
    return U;
  }
  Interval interval(const Box& b) const override {
    Scratch<Interval> x(c_.size());
    return terms(b, x);
  }
  double lipschitz() const override {
    double L = 0;
    for (const auto& c : c_) L = std::max(L, c->lipschitz());
    return L;
  }
  double lipschitz(const Box& b) const override {
    Scratch<Interval> x(c_.size());
    const Interval U = terms(b, x);
    double sum = 0, L_max = 0;
    for (size_t i = 0; i < c_.size(); ++i) {
      const double Li = c_[i]->lipschitz(b);
      const double v = x[i].lo > 0 ? std::min(1.0, std::pow(U.hi / x[i].lo, n_ + 1)) : 1.0;
      sum += chain(v, Li);
      L_max = std::max(L_max, Li);
    }
    return std::min(L_max, sum * (1 + 1e-13));
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

 private:
  // m·(Σ (m/x_i)^n)^(-1/n) with m = min x_i: every ratio is <= 1, so n = 20 cannot overflow.
  double combine(const double* x) const {
    double m = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < c_.size(); ++i) m = std::min(m, x[i]);
    if (!(m > 0)) return 0;
    double s = 0;
    for (size_t i = 0; i < c_.size(); ++i) s += std::pow(m / x[i], n_);
    return m * std::pow(s, -1 / n_);
  }
  Interval terms(const Box& b, Scratch<Interval>& x) const {
    Scratch<double> lo(c_.size()), hi(c_.size());
    for (size_t i = 0; i < c_.size(); ++i) {
      x[i] = c_[i]->interval(b);
      lo[i] = std::max(0.0, x[i].lo);
      hi[i] = std::max(0.0, x[i].hi);
    }
    // pow is faithfully rounded: widen by a relative margin well above its error.
    return {std::max(0.0, combine(lo.data()) * (1 - 1e-13)), combine(hi.data()) * (1 + 1e-13)};
  }

  std::vector<NodePtr> c_;
  double n_;
};

// (Σ x_i^n)^(1/n) with x_i clamped at 0   — 000 Eq. 6 B_RI^cg, docs/math.md §5.3.
// Partials (x_i/I)^(n-1) = w_i^((n-1)/n) with Σ w_i = 1 have l_q norm 1 (1/n + 1/q = 1) for
// n >= 1, so |∇I| <= (Σ L_i^n)^(1/n) by Hölder; no global bound for n < 1. Over a box the
// partials come from power_sum_partial_bound. Monotone, so the interval is the power sum of the
// children's intervals. region: I >= max x_i, so {I <= c} ⊂ ∩ {x_i <= c}; I <= k^(1/n) max x_i,
// so {I >= c} ⊂ ∪ {x_i >= c / k^(1/n)}.
class SuperEllipsoidalIntersection final : public FieldNode {
 public:
  SuperEllipsoidalIntersection(std::vector<NodePtr> children, double n)
      : c_(std::move(children)), n_(n) {
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
    Scratch<double> x(k), d(k);
    Scratch<Vec3> g(k);
    for (size_t i = 0; i < k; ++i) x[i] = std::max(0.0, c_[i]->eval(p, grad ? &g[i] : nullptr));
    const double f = power_sum(x.data(), static_cast<int>(k), n_, grad ? d.data() : nullptr);
    if (grad) {
      *grad = {};
      for (size_t i = 0; i < k; ++i) *grad += g[i] * d[i];
    }
    return f;
  }
  Interval interval(const Box& b) const override {
    Scratch<Interval> x(c_.size());
    return terms(b, x);
  }
  double lipschitz() const override { return global_L_; }
  double lipschitz(const Box& b) const override {
    Scratch<Interval> x(c_.size());
    const Interval f = terms(b, x);
    Scratch<double> Lb(c_.size());
    double sum = 0;
    for (size_t i = 0; i < c_.size(); ++i) {
      Lb[i] = c_[i]->lipschitz(b);
      sum += chain(power_sum_partial_bound(x[i], f, n_), Lb[i]);
    }
    double L = sum * (1 + 1e-13);
    if (n_ >= 1)
      L = std::min(L, power_sum(Lb.data(), static_cast<int>(c_.size()), n_, nullptr) * (1 + 1e-13));
    return std::isnan(L) ? global_L_ : std::min(global_L_, L);
  }
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

 private:
  Interval terms(const Box& b, Scratch<Interval>& x) const {
    for (size_t i = 0; i < c_.size(); ++i) x[i] = c_[i]->interval(b);
    return power_sum(x.data(), static_cast<int>(c_.size()), n_);
  }

  std::vector<NodePtr> c_;
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

// Parallel planes, one-branch plane and the (modulated) generalized distance function
// (docs/math.md §2.3, §2.4, §2.7, §2.10). Normals are normalised, so a is the distance to a plane.
#include <cmath>
#include <limits>

#include "distance_params.h"
#include "distances.h"
#include "gauge.h"
#include "one_sided.h"
#include "planes.h"
#include "program.h"
#include "scratch.h"

namespace softtrace {

namespace {

// One instruction with the parameters inline, in plane_params' order.
int compile_plane(ProgramBuilder& b, int reg, Op op, const PlaneParams& m) {
  Instr i{op};
  i.in = reg;
  i.out = b.new_slot();
  i.a = b.consts({m.n.x, m.n.y, m.n.z, m.a});
  return b.emit(i);
}

// |X·n|/a   — 000 Eq. 2 (planes), 002 f_p, docs/math.md §2.3. The kernels: planes.h.
class ParallelPlanes final : public FieldNode {
 public:
  ParallelPlanes(const Vec3& n, double a) : m_{n, a} {}

  double eval(const Vec3& p, Vec3* grad) const override { return parallel_planes(m_, p, grad); }
  Interval interval(const Box& b) const override {
    Interval f;
    double L;
    parallel_planes_bounds(m_, dot_range(b, m_.n), &f, &L);
    return f;
  }
  double lipschitz() const override { return 1 / m_.a; }
  // {f <= c} is a slab: unbounded, so region() keeps the default.
  int compile(ProgramBuilder& b, int reg) const override {
    return compile_plane(b, reg, Op::ParallelPlanes, m_);
  }

 private:
  PlaneParams m_;
};

// [X·n]_+/a   — 002 §4.5 f_o (R4), docs/math.md §2.4. The kernels: planes.h.
class OneBranchPlane final : public FieldNode {
 public:
  OneBranchPlane(const Vec3& n, double a) : m_{n, a} {}

  double eval(const Vec3& p, Vec3* grad) const override { return one_branch_plane(m_, p, grad); }
  Interval interval(const Box& b) const override {
    Interval f;
    double L;
    one_branch_plane_bounds(m_, dot_range(b, m_.n), &f, &L);
    return f;
  }
  double lipschitz() const override { return 1 / m_.a; }
  double lipschitz(const Box& b) const override {
    Interval f;
    double L;
    one_branch_plane_bounds(m_, dot_range(b, m_.n), &f, &L);
    return L;
  }
  int compile(ProgramBuilder& b, int reg) const override {
    return compile_plane(b, reg, Op::OneBranchPlane, m_);
  }

 private:
  PlaneParams m_;
};

// (Σ_i u_i^n)^(1/n), u_i = [X·n_i]_+/(t_{2i-1} a_i) + [-X·n_i]_+/(t_{2i} a_i)
//   — 000 Eq. 4, 002 Eq. 16 with AMBIGUITY A2 (R3); docs/math.md §2.7, §2.10.
// Bounds. ∇f = N^T v with N the unit normals as rows and v_i = ∂f/∂u_i · u_i'. For n >= 1 the
// partials have l_q norm 1 (1/n + 1/q = 1) and |u_i'| <= r_i = 1/(a_i min t), so
//   |∇f| <= Σ ∂_i r_i <= ||r||_n                                      (Hölder), and
//   |∇f| <= σ_max(N)·|v|_2 <= σ_max(N)·gauge_lipschitz(r)             (l_q -> l_2 norm of diag r),
// with σ_max(N)^2 = λ_max(N^T N) <= min(trace, max row sum). With the axes as normals σ = 1 and
// the second bound is the LP metric's. Over a box, ∂_i and u_i' are bounded from the intervals.
// region(c, Below): f <= c forces every u_i <= c, i.e. X·n_i ∈ [-c t_{2i} a_i, c t_{2i-1} a_i];
// any three independent normals then bound X (X = N3^{-1} s, interval arithmetic).
class GeneralizedDistance final : public FieldNode {
 public:
  GeneralizedDistance(std::vector<Vec3> normals, std::vector<OneSidedTerm> terms, double n)
      : n_(std::move(normals)), t_(std::move(terms)), e_(n) {
    global_L_ = std::numeric_limits<double>::infinity();
    double G[3][3] = {};
    for (const Vec3& v : n_)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) G[i][j] += v[i] * v[j];
    double trace = 0, row_sum = 0;
    for (int i = 0; i < 3; ++i) {
      trace += G[i][i];
      row_sum = std::max(row_sum, std::abs(G[i][0]) + std::abs(G[i][1]) + std::abs(G[i][2]));
    }
    sigma_ = std::sqrt(std::min(trace, row_sum)) * (1 + 1e-12);
    if (e_ < 1) return;
    std::vector<double> r;
    for (const auto& t : t_) r.push_back(t.slope());
    const int k = static_cast<int>(r.size());
    global_L_ =
        std::min(power_sum(r.data(), k, e_, nullptr), sigma_ * gauge_lipschitz(r.data(), k, e_));
    global_L_ *= 1 + 1e-12;
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = n_.size();
    Scratch<double> u(k), du(k), dfdu(k);
    for (size_t i = 0; i < k; ++i) u[i] = t_[i].value(dot(p, n_[i]), &du[i]);
    const double f = power_sum(u.data(), static_cast<int>(k), e_, grad ? dfdu.data() : nullptr);
    if (grad) {
      *grad = {};
      for (size_t i = 0; i < k; ++i) *grad += n_[i] * (dfdu[i] * du[i]);
    }
    return f;
  }
  Interval interval(const Box& b) const override {
    Scratch<Interval> s(n_.size()), u(n_.size());
    return terms(b, s, u);
  }
  double lipschitz() const override { return global_L_; }
  double lipschitz(const Box& b) const override {
    Scratch<Interval> s(n_.size()), u(n_.size());
    const Interval f = terms(b, s, u);
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n_.size(); ++i) {
      const double g = chain(power_sum_partial_bound(u[i], f, e_), t_[i].slope(s[i]));
      sum += g;
      sum2 += g * g;
    }
    const double L = std::min(sum, sigma_ * std::sqrt(sum2)) * (1 + 1e-13);
    return std::isnan(L) ? global_L_ : std::min(global_L_, L);
  }
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    Box best = Box::unbounded();
    const size_t k = n_.size();
    for (size_t i = 0; i < k; ++i)
      for (size_t j = i + 1; j < k; ++j)
        for (size_t l = j + 1; l < k; ++l) best = best.intersected(solve(level, i, j, l));
    return best;
  }

 private:
  Interval terms(const Box& b, Scratch<Interval>& s, Scratch<Interval>& u) const {
    for (size_t i = 0; i < n_.size(); ++i) {
      s[i] = dot_range(b, n_[i]);
      u[i] = t_[i].range(s[i]);
    }
    return power_sum(u.data(), static_cast<int>(n_.size()), e_);
  }
  // The box of {X : X·n_m ∈ below_m(c), m = i, j, l}; unbounded for a near-singular triple.
  Box solve(double c, size_t i, size_t j, size_t l) const {
    const Vec3 cols[3] = {cross(n_[j], n_[l]), cross(n_[l], n_[i]), cross(n_[i], n_[j])};
    const double det = dot(n_[i], cols[0]);
    if (std::abs(det) < 1e-6) return Box::unbounded();
    const Interval s[3] = {t_[i].below(c), t_[j].below(c), t_[l].below(c)};
    Box b;
    for (int a = 0; a < 3; ++a) {
      Interval x(0);
      for (int m = 0; m < 3; ++m) x = x + Interval(cols[m][a] / det) * s[m];
      // The inverse's rounding is relative ~1e-16/|det| <= 1e-10: pad far above it.
      const double pad = 1e-9 * std::max(std::abs(x.lo), std::abs(x.hi)) + 1e-300;
      b.lo[a] = x.lo - pad;
      b.hi[a] = x.hi + pad;
    }
    return b;
  }

  std::vector<Vec3> n_;
  std::vector<OneSidedTerm> t_;
  double e_, sigma_, global_L_;
};

}  // namespace

NodePtr create_parallel_planes(const Params& p, const BuildContext&) {
  return std::make_unique<ParallelPlanes>(unit_normal(p, "normal"), p.number("a"));
}

NodePtr create_one_branch_plane(const Params& p, const BuildContext&) {
  return std::make_unique<OneBranchPlane>(unit_normal(p, "normal"), p.number("a"));
}

NodePtr create_generalized_distance(const Params& p, const BuildContext&) {
  std::vector<Vec3> normals = p.vec3s("normals");
  const size_t k = normals.size();
  for (size_t i = 0; i < k; ++i) {
    const double l = length(normals[i]);
    p.check_at(l > 0, "normals", i, "expected a non-zero normal");
    normals[i] = normals[i] / l;
  }
  const std::vector<double> a = p.numbers_or_scalar("a", k);
  const double n = p.number("n");
  const std::vector<double> tp = side_lengths(p, "t_pos", k), tn = side_lengths(p, "t_neg", k);
  std::vector<OneSidedTerm> terms;
  for (size_t i = 0; i < k; ++i) terms.push_back({a[i] * tp[i], a[i] * tn[i], 0.0});
  return std::make_unique<GeneralizedDistance>(std::move(normals), std::move(terms), n);
}

}  // namespace softtrace

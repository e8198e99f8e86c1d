// Parallel planes, one-branch plane and the (modulated) generalized distance function
// (docs/math.md §2.3, §2.4, §2.7, §2.10). Normals are normalised, so a is the distance to a plane.
#include <cmath>

#include "describe/distance_params.h"
#include "kernels/generalized_distance.h"
#include "kernels/one_sided.h"
#include "kernels/planes.h"
#include "model/distances.h"
#include "model/kernel_node.h"
#include "model/program_builder.h"
#include "program/ops/plane_ops.h"

namespace softtrace {

namespace {

// |X·n|/a (both = true)   — 000 Eq. 2 (planes), 002 f_p, docs/math.md §2.3; [X·n]_+/a (both =
// false)   — 002 §4.5 f_o (R4), docs/math.md §2.4. The kernels: planes.h. The nodes are
// KernelNode<OnePlane<both>>.
template <bool both>
struct OnePlane {
  using Params = PlaneParams;
  using OpKernel = PlaneOp<both>;
  static constexpr Op kOp = both ? Op::ParallelPlanes : Op::OneBranchPlane;
  static double value(const PlaneParams& m, const Vec3& p, Vec3* grad) {
    return OpKernel::kernel(m, p, grad);
  }
  static void bounds(const PlaneParams& m, const Box& b, Interval* value, double* lipschitz) {
    (both ? parallel_planes_bounds : one_branch_plane_bounds)(m, dot_range(b, m.n), value,
                                                              lipschitz);
  }
  static double lipschitz(const PlaneParams& m) { return 1 / m.a; }
  // {f <= c} is a slab, a half-space or empty: no finite region.
  static Box region(const PlaneParams&, double, Side) { return Box::unbounded(); }
};

// (Σ_i u_i^n)^(1/n), u_i = [X·n_i]_+/(t_{2i-1} a_i) + [-X·n_i]_+/(t_{2i} a_i)
//   — 000 Eq. 4, 002 Eq. 16 with AMBIGUITY A2 (R3); docs/math.md §2.7, §2.10. The kernels and
// why their bounds hold: generalized_distance.h.
// region(c, Below): f <= c forces every u_i <= c, i.e. X·n_i ∈ [-c t_{2i} a_i, c t_{2i-1} a_i];
// any three independent normals then bound X (X = N3^{-1} s, interval arithmetic).
class GeneralizedDistance final : public FieldNode {
 public:
  GeneralizedDistance(std::vector<Vec3> normals, std::vector<OneSidedTerm> terms, double n)
      : n_(std::move(normals)),
        t_(std::move(terms)),
        c_(generalized_distance_constants(n_, t_, n)) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    return generalized_distance(params(), p, grad);
  }
  double lipschitz() const override { return params().global_L(); }
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
  // One instruction: the normal count in n, the parameters in GeneralizedDistanceParams' layout.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.single(Op::GenDistance, reg, GenDistanceOp::constants(c_),
                    static_cast<int32_t>(n_.size()));
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    NodeBounds out;
    generalized_distance_bounds(params(), b, &out.value, &out.lipschitz);
    return out;
  }

  GeneralizedDistanceParams params() const { return {c_.data(), static_cast<int>(n_.size())}; }
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
  std::vector<double> c_;  // the kernels' parameters (generalized_distance.h)
};

}  // namespace

NodePtr create_parallel_planes(const Params& p, const BuildContext&) {
  return std::make_unique<KernelNode<OnePlane<true>>>(
      PlaneParams{unit_normal(p, "normal"), p.number("a")});
}

NodePtr create_one_branch_plane(const Params& p, const BuildContext&) {
  return std::make_unique<KernelNode<OnePlane<false>>>(
      PlaneParams{unit_normal(p, "normal"), p.number("a")});
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

// Perlin's set blends, sharp min/max and the complement (docs/math.md §1, §5.2).
#include <algorithm>
#include <cmath>
#include <limits>

#include "describe/building.h"
#include "kernels/complement.h"
#include "kernels/perlin.h"
#include "math/scratch.h"
#include "model/blends.h"
#include "model/nary_node.h"
#include "model/node_util.h"
#include "model/program_builder.h"
#include "model/strength.h"
#include "program/ops/nary_ops.h"
#include "program/ops/potential_ops.h"

namespace softtrace {

namespace {

// 1 - Π(1 - f_i), Π f_i, f_1 Π_{i>=2} (1 - f_i)   — 002 Eqs. 4–6, docs/math.md §5.2 (perlin.h).
class Perlin final : public NaryNode<Perlin> {
 public:
  using Mode = PerlinMode;
  Perlin(std::vector<NodePtr> c, Mode m) : NaryNode(std::move(c)), mode_(m) {
    std::vector<Interval> G;
    for (size_t i = 0; i < c_.size(); ++i) G.push_back(perlin_factor(m, i, global_range(*c_[i])));
    std::vector<double> L;
    for (const auto& c : c_) L.push_back(c->lipschitz());
    global_L_ = perlin_slope(G.data(), L.data(), G.size());
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = c_.size();
    Scratch<double> g(k);
    Scratch<Vec3> gg(k);
    for (size_t i = 0; i < k; ++i) g[i] = c_[i]->eval(p, grad ? &gg[i] : nullptr);
    return perlin(mode_, g.data(), gg.data(), k, grad);
  }
  double lipschitz() const override { return global_L_; }
  // Soft children (f >= 0): B > 0 needs some f_i > 0 (union), every f_i > 0 (intersection), or
  // f_1 > 0 (difference); the support boxes follow.
  Box region(double level, Side side) const override {
    if (side == Side::Below || level <= 0) return Box::unbounded();
    const double tiny = std::numeric_limits<double>::min();
    if (mode_ == Mode::Difference) return c_[0]->region(tiny, side);
    Box b = mode_ == Mode::Union ? Box() : Box::unbounded();
    for (const auto& c : c_) {
      const Box r = c->region(tiny, side);
      b = mode_ == Mode::Union ? b.united(r) : b.intersected(r);
    }
    return b;
  }

  // The children's code as a group (never pruned), then one instruction with the mode and the
  // global bound inline.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.nary(Op::Perlin, c_, reg, b.consts(PerlinOp::constants(mode_, global_L_)));
  }

 private:
  friend NaryNode;

  // Interval arithmetic on the product, and [PE-3]'s bound, from the children's (perlin.h).
  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    const size_t k = c_.size();
    return {perlin_interval(mode_, I, k), perlin_lipschitz(mode_, I, L, k, global_L_)};
  }

  Mode mode_;
  double global_L_;
};

// min / max of the children (sharp union/intersection baselines, docs/math.md §1)
class MinMax final : public NaryNode<MinMax> {
 public:
  MinMax(std::vector<NodePtr> c, bool is_min) : NaryNode(std::move(c)), min_(is_min) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    double best = 0;
    Vec3 g;
    for (size_t i = 0; i < c_.size(); ++i) {
      const double v = c_[i]->eval(p, grad ? &g : nullptr);
      if (i == 0 || (min_ ? v < best : v > best)) {
        best = v;
        if (grad) *grad = g;
      }
    }
    return best;
  }
  // |min(a) - min(b)| <= max_i |a_i - b_i|.
  double lipschitz() const override {
    double L = 0;
    for (const auto& c : c_) L = std::max(L, c->lipschitz());
    return L;
  }
  // min >= l iff every f_i >= l; min <= c iff some f_i <= c (and dually for max).
  Box region(double level, Side side) const override {
    const bool all = min_ == (side == Side::Above);
    Box b = all ? Box::unbounded() : Box();
    for (const auto& c : c_) {
      const Box r = c->region(level, side);
      b = all ? b.intersected(r) : b.united(r);
    }
    return b;
  }
  int compile(ProgramBuilder& b, int reg) const override {
    return b.nary(min_ ? Op::Min : Op::Max, c_, reg);
  }

 private:
  friend NaryNode;

  // The interval min/max of the intervals; over a box only children that can be the extreme
  // somewhere in it (their interval reaches the result's interval) count towards the bound.
  NodeBounds combine(const Box&, const Interval* I, const double* L) const {
    const size_t k = c_.size();
    Interval r = I[0];
    for (size_t i = 1; i < k; ++i) r = min_ ? min(r, I[i]) : max(r, I[i]);
    double Lr = 0;
    for (size_t i = 0; i < k; ++i)
      if (min_ ? I[i].lo <= r.hi : I[i].hi >= r.lo) Lr = std::max(Lr, L[i]);
    return {r, Lr};
  }

  bool min_;
};

// The complement of docs/math.md §1: soft 1 - f, zero -f, constructive 1/f (guarded)
class Complement final : public FieldNode {
 public:
  Complement(NodePtr c, Convention conv) : c_(std::move(c)), conv_(conv) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    return complement(conv_, c_->eval(p, grad), grad);
  }
  double lipschitz() const override { return complement_lipschitz(conv_, c_->lipschitz()); }
  Box region(double level, Side side) const override {
    const Side other = side == Side::Above ? Side::Below : Side::Above;
    switch (conv_) {
      case Convention::Soft:
        return c_->region(1 - level, other);
      case Convention::Zero:
        return c_->region(-level, other);
      case Convention::Constructive:
        // 1/max(f, floor) >= l > 0 iff f <= 1/l (when 1/l >= floor); <= c iff f >= 1/c.
        if (side == Side::Above) {
          if (level <= 0) return Box::unbounded();
          return 1 / level < kCgFloor ? Box() : c_->region(1 / level, other);
        }
        if (level <= 0) return Box();
        return 1 / level <= kCgFloor ? Box::unbounded() : c_->region(1 / level, other);
    }
    return Box::unbounded();
  }
  // The child's code, then one instruction with the convention inline.
  int compile(ProgramBuilder& b, int reg) const override {
    return b.single(Op::Complement, b.compile(*c_, reg), ComplementOp::constants(conv_));
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    const NodeBounds f = c_->bounds(b);
    return {complement_interval(conv_, f.value), complement_lipschitz(conv_, f.value, f.lipschitz)};
  }

  NodePtr c_;
  Convention conv_;
};

}  // namespace

NodePtr create_perlin_union(const Params& p, const BuildContext& ctx) {
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  refuse_negative_strength(p, ctx.kind->name);
  return std::make_unique<Perlin>(std::move(c), Perlin::Mode::Union);
}
NodePtr create_perlin_intersection(const Params& p, const BuildContext& ctx) {
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  refuse_negative_strength(p, ctx.kind->name);
  return std::make_unique<Perlin>(std::move(c), Perlin::Mode::Intersection);
}
NodePtr create_perlin_difference(const Params& p, const BuildContext& ctx) {
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  refuse_negative_strength(p, ctx.kind->name);
  return std::make_unique<Perlin>(std::move(c), Perlin::Mode::Difference);
}
NodePtr create_min(const Params& p, const BuildContext& ctx) {
  return std::make_unique<MinMax>(build_children(p, "children", ctx), true);
}
NodePtr create_max(const Params& p, const BuildContext& ctx) {
  return std::make_unique<MinMax>(build_children(p, "children", ctx), false);
}
NodePtr create_complement(const Params& p, const BuildContext& ctx) {
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  return std::make_unique<Complement>(std::move(c[0]), ctx.convention);
}

}  // namespace softtrace

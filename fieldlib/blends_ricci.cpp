// Ricci's super-ellipsoidal operators (docs/math.md §5.3 constructive, §5.4 soft). Every one is a
// power mean B = (Σ g_i^q)^(1/q) with q = n or q = -n of arguments g_i = f_i, 1 - f_i (soft
// complement) or 1/f_i (constructive complement):
//   soft:         union q = n; intersection q = -n; difference q = -n with g = (f1, 1-f2, ...)
//   constructive: union q = -n; intersection q = n; difference q = n with g = (f1, 1/f2, ...)
// Bounds: B is non-decreasing in every g_i, so its interval is B at the ends of the g intervals.
// q = n: ∂B/∂g_i = (g_i/B)^(n-1) (power_sum_partial_bound per box) and, for n >= 1, Hölder with
// Σ (g_i/B)^n = 1 gives |∇B| <= (Σ (c_i L_i)^n)^(1/n) ([RS-3]); n < 1 has no global bound.
// q = -n: ∂B/∂g_i = (B/g_i)^(n+1) <= (B/g_i)^n, which sum to 1, so |∇B| <= max_i c_i L_i, and
// per box Σ min(1, (B.hi/g_i.lo)^(n+1)) c_i L_i. c_i = sup|dg_i/df_i| (1, or 1/f^2 for 1/f).
// Regions: q = n gives max g <= B <= k^(1/n) max g; q = -n gives k^(-1/n) min g <= B <= min g.
#include <algorithm>
#include <cmath>
#include <limits>

#include "blends.h"
#include "gauge.h"
#include "node_util.h"
#include "registry.h"
#include "scratch.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Arg { Same, SoftComplement, CgComplement };

// (Σ g_i^q)^(1/q)   — 000 Eq. 6, 002 Eqs. 7–8
class Ricci final : public FieldNode {
 public:
  Ricci(std::vector<NodePtr> c, std::vector<Arg> args, bool positive, double n)
      : c_(std::move(c)), args_(std::move(args)), positive_(positive), n_(n) {
    std::vector<double> cL;
    for (size_t i = 0; i < c_.size(); ++i)
      cL.push_back(flat_product(arg_slope(i, global_range(*c_[i])), c_[i]->lipschitz()));
    global_L_ = combine(cL.data(), static_cast<int>(cL.size()));
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    const size_t k = c_.size();
    Scratch<double> g(k), dg(k), dB(k);
    Scratch<Vec3> gf(k);
    for (size_t i = 0; i < k; ++i) g[i] = arg(i, c_[i]->eval(p, grad ? &gf[i] : nullptr), &dg[i]);
    const double B = mean(g.data(), grad ? dB.data() : nullptr);
    if (grad) {
      *grad = {};
      for (size_t i = 0; i < k; ++i)
        if (dB[i] != 0 && dg[i] != 0) *grad += gf[i] * (dB[i] * dg[i]);
    }
    return B;
  }
  Interval interval(const Box& b) const override {
    const size_t k = c_.size();
    Scratch<Interval> G(k);
    for (size_t i = 0; i < k; ++i) G[i] = arg_range(i, c_[i]->interval(b));
    return range(G.data());
  }
  double lipschitz() const override { return global_L_; }
  double lipschitz(const Box& b) const override {
    const size_t k = c_.size();
    Scratch<Interval> G(k);
    Scratch<double> cL(k);
    for (size_t i = 0; i < k; ++i) {
      const Interval f = c_[i]->interval(b);
      G[i] = arg_range(i, f);
      cL[i] = flat_product(arg_slope(i, f), c_[i]->lipschitz(b));
    }
    const Interval B = range(G.data());
    double s = 0;
    for (size_t i = 0; i < k; ++i) {
      double a;
      if (positive_) {
        a = power_sum_partial_bound({std::max(0.0, G[i].lo), std::max(0.0, G[i].hi)}, B, n_);
      } else {
        a = G[i].lo > 0 ? std::min(1.0, std::pow(B.hi / G[i].lo, n_ + 1) * (1 + 1e-13)) : 1;
      }
      s += flat_product(a, cL[i]);
    }
    return std::min({global_L_, combine(cL.data(), static_cast<int>(k)), s * (1 + 1e-12)});
  }
  Box region(double level, Side side) const override {
    const double k = static_cast<double>(c_.size());
    // B >= 0 always: {B <= c < 0} is empty.
    if (side == Side::Below && level < 0) return Box();
    const bool any = positive_ == (side == Side::Above);  // a union of the arguments' regions
    double l = level;
    if (positive_ && side == Side::Above) l = level * std::pow(k, -1 / n_);
    if (!positive_ && side == Side::Below) l = level * std::pow(k, 1 / n_);
    if (side == Side::Above && level <= 0) return Box::unbounded();
    Box b = any ? Box() : Box::unbounded();
    for (size_t i = 0; i < c_.size(); ++i) {
      const Box r = arg_region(i, l, side);
      b = any ? b.united(r) : b.intersected(r);
    }
    return b;
  }

 private:
  double arg(size_t i, double f, double* dg) const {
    switch (args_[i]) {
      case Arg::Same:
        *dg = 1;
        return f;
      case Arg::SoftComplement:
        *dg = -1;
        return 1 - f;
      case Arg::CgComplement:
        if (f <= kCgFloor) {
          *dg = 0;
          return 1 / kCgFloor;
        }
        *dg = -1 / (f * f);
        return 1 / f;
    }
    return f;
  }
  Interval arg_range(size_t i, Interval f) const {
    switch (args_[i]) {
      case Arg::Same:
        return f;
      case Arg::SoftComplement:
        return Interval(1) - f;
      case Arg::CgComplement:
        return {iv::down(1 / std::max(f.hi, kCgFloor)), iv::up(1 / std::max(f.lo, kCgFloor))};
    }
    return f;
  }
  double arg_slope(size_t i, Interval f) const {
    if (args_[i] != Arg::CgComplement) return 1;
    const double lo = std::max(f.lo, kCgFloor);
    return 1 / (lo * lo) * (1 + 1e-12);
  }
  // The region of child i where its argument g_i >= l (Above) or <= l (Below).
  Box arg_region(size_t i, double l, Side side) const {
    const Side other = side == Side::Above ? Side::Below : Side::Above;
    switch (args_[i]) {
      case Arg::Same:
        return c_[i]->region(l, side);
      case Arg::SoftComplement:
        return c_[i]->region(1 - l, other);
      case Arg::CgComplement:
        if (side == Side::Above) {
          if (l <= 0) return Box::unbounded();
          return 1 / l < kCgFloor ? Box() : c_[i]->region(1 / l, other);
        }
        if (l <= 0) return Box();
        return 1 / l <= kCgFloor ? Box::unbounded() : c_[i]->region(1 / l, other);
    }
    return Box::unbounded();
  }

  // B(g) and ∂B/∂g_i; negative arguments count as 0 (q = n) or make B = 0 (q = -n, docs/math.md
  // §5.4).
  double mean(const double* g, double* dB) const {
    const int k = static_cast<int>(c_.size());
    if (positive_) {
      Scratch<double> u(k);
      for (int i = 0; i < k; ++i) u[i] = std::max(g[i], 0.0);
      return power_sum(u.data(), k, n_, dB);
    }
    double m = kInf;
    for (int i = 0; i < k; ++i) m = std::min(m, g[i]);
    if (m <= 0) {
      if (dB) std::fill(dB, dB + k, 0.0);
      return 0;
    }
    double s = 0;
    for (int i = 0; i < k; ++i) s += std::pow(m / g[i], n_);  // in [1, k]: no overflow
    const double B = m * std::pow(s, -1 / n_);
    if (dB)
      for (int i = 0; i < k; ++i) dB[i] = std::pow(B / g[i], n_ + 1);
    return B;
  }
  // G holds one interval per child.
  Interval range(const Interval* G) const {
    const int k = static_cast<int>(c_.size());
    if (positive_) return power_sum(G, k, n_);
    Scratch<double> lo(k), hi(k);
    for (int i = 0; i < k; ++i) {
      lo[i] = G[i].lo;
      hi[i] = G[i].hi;
    }
    return {std::max(0.0, mean(lo.data(), nullptr) * (1 - 1e-13)),
            mean(hi.data(), nullptr) * (1 + 1e-13)};
  }
  // The derivative-free bound from c_i L_i (header comment).
  double combine(const double* cL, int k) const {
    for (int i = 0; i < k; ++i)
      if (!std::isfinite(cL[i])) return kInf;
    if (positive_) {
      if (n_ < 1) return kInf;
      return power_sum(cL, k, n_, nullptr) * (1 + 1e-12);
    }
    return *std::max_element(cL, cL + k);
  }

  std::vector<NodePtr> c_;
  std::vector<Arg> args_;
  bool positive_;
  double n_, global_L_;
};

enum class SetOp { Union, Intersection, Difference };

NodePtr create_ricci(const Params& p, const BuildContext& ctx, SetOp op) {
  if (ctx.convention == Convention::Zero)
    p.fail("type", "ricci_* applies to soft or constructive objects (docs/math.md §5.3, §5.4)");
  const double n = p.number("n");
  std::vector<NodePtr> c = build_children(p, "children", ctx);
  const bool soft = ctx.convention == Convention::Soft;
  std::vector<Arg> args(c.size(), Arg::Same);
  if (op == SetOp::Difference)
    std::fill(args.begin() + 1, args.end(), soft ? Arg::SoftComplement : Arg::CgComplement);
  // Soft union and constructive intersection/difference are the q = n means.
  const bool positive = soft ? op == SetOp::Union : op != SetOp::Union;
  return std::make_unique<Ricci>(std::move(c), std::move(args), positive, n);
}

}  // namespace

NodePtr create_ricci_union(const Params& p, const BuildContext& ctx) {
  return create_ricci(p, ctx, SetOp::Union);
}
NodePtr create_ricci_intersection(const Params& p, const BuildContext& ctx) {
  return create_ricci(p, ctx, SetOp::Intersection);
}
NodePtr create_ricci_difference(const Params& p, const BuildContext& ctx) {
  return create_ricci(p, ctx, SetOp::Difference);
}

}  // namespace softtrace

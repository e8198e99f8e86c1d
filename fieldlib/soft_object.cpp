#include "soft_object.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "modulation_check.h"
#include "node_util.h"
#include "potentials.h"
#include "program.h"
#include "radius_transforms.h"
#include "registry.h"

namespace softtrace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// w1 = d/f - 1 is capped here where f -> 0 away from the skeleton; T_n/T_l are then ~0.5 on the
// outer branch, the limit w1 -> infinity.
constexpr double kWMax = 1e6;

// P ∘ d   — 000 Eq. 9, 002 Eq. 1
class SoftObject final : public FieldNode {
 public:
  SoftObject(NodePtr distance, PotentialPtr potential)
      : d_(std::move(distance)), P_(std::move(potential)) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const double d = d_->eval(p, grad);
    double dP;
    const double v = P_->eval(d, grad ? &dP : nullptr);
    if (grad) *grad = dP == 0 ? Vec3{} : *grad * dP;
    return v;
  }
  Interval interval(const Box& b) const override { return P_->interval(d_->interval(b)); }
  double lipschitz() const override { return flat_product(P_->lipschitz(), d_->lipschitz()); }
  double lipschitz(const Box& b) const override {
    return flat_product(P_->lipschitz(d_->interval(b)), d_->lipschitz(b));
  }
  void bounds(const Box& b, Interval* value, double* L) const override {
    Interval d;
    double Ld;
    d_->bounds(b, &d, &Ld);
    *value = P_->interval(d);
    *L = flat_product(P_->lipschitz(d), Ld);
  }
  Box region(double level, Side side) const override {
    if (side == Side::Above && level > 0) return d_->region(1, Side::Below);
    return Box::unbounded();
  }
  // The distance's code, then one potential instruction.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{P_->op()};
    i.in = b.compile(*d_, reg);
    i.out = b.new_slot();
    if (P_->op() == Op::Blanc) i.a = b.consts({P_->parameter()});
    return b.emit(i);
  }

 private:
  NodePtr d_;
  PotentialPtr P_;
};

// Where w comes from: a constant, w1 = d/f - 1 (T_an, T_al, contour; 002 Eq. 11, 000 Eq. 15) or
// w2 = 1 - d/f (T_sn, T_sr; 002 Eq. 12).
enum class WSource { Constant, Outer, Inner };

// P ∘ T ∘ d   — 000 Eqs. 13–15, 002 Eqs. 10–14, docs/math.md §4.2–§4.9
class TransformedSoftObject final : public FieldNode {
 public:
  TransformedSoftObject(NodePtr d, PotentialPtr P, std::unique_ptr<RadiusProfile> T, double w)
      : d_(std::move(d)), P_(std::move(P)), T_(std::move(T)), src_(WSource::Constant), w_(w) {
    support_ = region(std::numeric_limits<double>::min(), Side::Above);
  }
  TransformedSoftObject(NodePtr d, PotentialPtr P, std::unique_ptr<RadiusProfile> T, WSource src,
                        NodePtr f, double f_scale, double w_min)
      : d_(std::move(d)),
        P_(std::move(P)),
        T_(std::move(T)),
        src_(src),
        f_(std::move(f)),
        scale_(f_scale),
        w_min_(w_min) {
    support_ = region(std::numeric_limits<double>::min(), Side::Above);
  }

  double eval(const Vec3& p, Vec3* grad) const override {
    Vec3 gd, gf;
    const double d = d_->eval(p, grad ? &gd : nullptr);
    if (d <= 0) {  // the skeleton: T = 0 (§4.9), P'(0) = 0
      if (grad) *grad = {};
      return P_->eval(0, nullptr);
    }
    double w = w_, wd = 0, wf = 0;
    if (src_ != WSource::Constant) {
      const double f = scale_ * f_->eval(p, grad ? &gf : nullptr);
      w = parameter(d, f, &wd, &wf);
      gf = gf * scale_;
    }
    double Td, Tw, dP;
    const double T = T_->eval(d, w, &Td, &Tw);
    const double v = P_->eval(T, grad ? &dP : nullptr);
    if (grad) {
      if (dP == 0) {
        *grad = {};
      } else {
        const Vec3 gT = gd * (Td + Tw * wd) + gf * (Tw * wf);
        *grad = gT * dP;
      }
    }
    return v;
  }

  // Outside the support box the field is exactly 0: no bound is needed there. This matters in
  // blends, where every stretch box asks every child, and the decorrelated [d]/[f] bounds of a
  // far-away child are loose (measured on [002] Fig. 8(c): thousands of evaluations per ray).
  Interval interval(const Box& b) const override {
    if (outside_support(b)) return Interval(0);
    Interval I;
    refined(b, kRefine, &I, nullptr);
    return I;
  }

  double lipschitz() const override {
    if (src_ != WSource::Constant) return kInf;
    const double s = T_->slope_d({0, kInf}, Interval(w_));
    return flat_product(P_->lipschitz(), flat_product(s, d_->lipschitz()));
  }

  double lipschitz(const Box& b) const override {
    Interval I;
    double L;
    bounds(b, &I, &L);
    return L;
  }
  void bounds(const Box& b, Interval* value, double* L) const override {
    if (outside_support(b)) {
      *value = Interval(0);
      *L = 0;
      return;
    }
    refined(b, kRefine, value, L);
  }

  Box region(double level, Side side) const override {
    if (side != Side::Above || level <= 0) return Box::unbounded();
    switch (src_) {
      case WSource::Constant:
        return d_->region(T_->outer_end(w_), Side::Below);
      case WSource::Outer:
        return f_->region(0.5 / scale_, Side::Below)
            .united(d_->region(0.5 * (1 + w_min_), Side::Below));
      case WSource::Inner:
        return d_->region(1, Side::Below);
    }
    return Box::unbounded();
  }

 private:
  bool outside_support(const Box& b) const {
    return support_.bounded() && support_.intersected(b).empty();
  }

  struct Bounds {
    Interval d, f, r, w, T;  // r = d/f, unclamped
    double Ld = 0, Lf = 0;   // d's and f's (unscaled) Lipschitz bounds, where asked for
  };

  // [d]/[f] loses the correlation of d and f (their ratio is constant along rays from a common
  // centre), so [w] can reach the clamp although w stays well above it in the box; up to two
  // levels of octants, only where [w] is that wide, restore most of it (measured for T_sn on
  // boxes of 5 % of the object's size at its surface: bounds of 1e7 drop to ~1e2 against sampled
  // slopes of ~10). Every level is sound; the smaller bound is kept.
  static constexpr int kRefine = 2;  // octant levels: at most 8 + 64 sub-boxes
  // Octants cost up to 72 bounds; boxes above this fraction of the support's diagonal are not
  // refined. Those are the tracer's long segments, which it halves along the ray itself for a
  // bound or two (measured over scenes/ at 80x60 and 320x240: the same evaluations per ray, and
  // 0.2-0.7x the time on the contour and modulated scenes; 1/16 keeps the 5 % boxes of
  // SurfaceDefined.BoxBoundsStayUsefulAtTheSurface refined).
  static constexpr double kRefineMaxSize = 1.0 / 16;

  // The interval over b and, where L is non-null, the Lipschitz bound: each the tighter of b's own
  // and its octants' (one walk over the octants serves both).
  void refined(const Box& b, int levels, Interval* I, double* L) const {
    const Bounds B = bounds(b, L != nullptr);
    *I = P_->interval(B.T);
    if (L) *L = slope_bound(B);
    if (levels == 0 || !decorrelated(B, b) || !worth_refining(b)) return;
    Interval h(kInf, -kInf);
    double m = 0, Ls;
    for (const Box& s : octants(b)) {
      Interval Is;
      refined(s, levels - 1, &Is, L ? &Ls : nullptr);
      h = hull(h, Is);
      if (L) m = std::max(m, Ls);
    }
    *I = {std::max(I->lo, h.lo), std::min(I->hi, h.hi)};
    if (L) *L = std::min(*L, m);
  }
  bool decorrelated(const Bounds& B, const Box& b) const {
    return src_ != WSource::Constant && b.bounded() && B.w.lo < 0.25 * B.w.hi && B.T.lo < B.T.hi;
  }
  bool worth_refining(const Box& b) const {
    return !support_.bounded() || b.diagonal() <= kRefineMaxSize * support_.diagonal();
  }
  static std::array<Box, 8> octants(const Box& b) {
    std::array<Box, 8> out;
    const Vec3 c = b.center();
    for (int k = 0; k < 8; ++k)
      for (int i = 0; i < 3; ++i) {
        const bool hi = (k >> i) & 1;
        out[k].lo[i] = hi ? c[i] : b.lo[i];
        out[k].hi[i] = hi ? b.hi[i] : c[i];
      }
    return out;
  }

  // The Lipschitz bound over the box B was taken on (bounds(b, true)).
  double slope_bound(const Bounds& B) const {
    if (B.T.hi <= 0) return 0;  // T = 0: P(0) over the whole box
    const double LP = P_->lipschitz(B.T);
    if (LP == 0) return 0;
    const double dterm = flat_product(T_->slope_d(B.d, B.w), B.Ld);
    if (src_ == WSource::Constant) return std::min(lipschitz(), flat_product(LP, dterm));
    const double sw = T_->slope_w(B.d, B.w);
    double wterm = 0;
    if (sw > 0) {
      const double Lf = scale_ * B.Lf;
      const double G1 = B.f.lo > 0 ? B.Ld / B.f.lo + B.d.hi * Lf / (B.f.lo * B.f.lo) : kInf;
      const double G2 = B.r.hi * (B.Ld + B.r.hi * Lf);
      wterm = std::min(flat_product(sw, G1), flat_product(T_->slope_w_per_d(B.d, B.w), G2));
    }
    return flat_product(LP, (dterm + wterm) * (1 + 1e-12));
  }

  // w from d > 0 and f, clamped to [w_min, w_max] (§4.9), with ∂w/∂d and ∂w/∂f.
  double parameter(double d, double f, double* wd, double* wf) const {
    *wd = *wf = 0;
    const double hi = src_ == WSource::Outer ? kWMax : 1;
    if (f <= 0) return src_ == WSource::Outer ? kWMax : w_min_;  // condition (c) violated
    const double sign = src_ == WSource::Outer ? 1 : -1;
    const double w = src_ == WSource::Outer ? d / f - 1 : 1 - d / f;
    if (w <= w_min_) return w_min_;
    if (w >= hi) return hi;
    *wd = sign / f;
    *wf = -sign * d / (f * f);
    return w;
  }

  // With `slopes`, d's and f's Lipschitz bounds too, from the same calls as their intervals.
  Bounds bounds(const Box& b, bool slopes) const {
    Bounds B;
    Interval d;
    if (slopes) {
      d_->bounds(b, &d, &B.Ld);
    } else {
      d = d_->interval(b);
    }
    B.d = {std::max(0.0, d.lo), std::max(0.0, d.hi)};
    if (src_ == WSource::Constant) {
      B.w = Interval(w_);
      B.T = T_->image(B.d, B.w);
      return B;
    }
    Interval f;
    if (slopes) {
      f_->bounds(b, &f, &B.Lf);
    } else {
      f = f_->interval(b);
    }
    B.f = {iv::down(scale_ * f.lo), iv::up(scale_ * f.hi)};
    if (B.f.lo > 0) {
      B.r = B.d / B.f;
    } else {  // f can reach 0 (or below, where w is capped): no upper bound on d/f
      B.r = {B.f.hi > 0 ? iv::down(B.d.lo / B.f.hi) : kInf, kInf};
    }
    const auto clamp = [&](double w, double hi) { return std::min(std::max(w, w_min_), hi); };
    if (src_ == WSource::Outer) {
      B.w = {clamp(iv::down(B.r.lo - 1), kWMax), clamp(iv::up(B.r.hi - 1), kWMax)};
      // [TA-1] with the clamp: T = 1 where d >= 0.5(1+w_min) and f >= 0.5.
      if (B.d.lo > 0.5 * (1 + w_min_) * (1 + 1e-12) && B.f.lo > 0.5 * (1 + 1e-12)) {
        B.T = Interval(1);
        return B;
      }
    } else {
      B.w = {clamp(iv::down(1 - B.r.hi), 1), clamp(iv::up(1 - B.r.lo), 1)};
      // [TS-1] with the clamp: T = 0 where d < 0.5(1-w_min) and f < 0.5.
      if (B.d.hi < 0.5 * (1 - w_min_) * (1 - 1e-12) && B.f.hi < 0.5 * (1 - 1e-12)) {
        B.T = Interval(0);
        return B;
      }
    }
    B.T = T_->image(B.d, B.w);
    return B;
  }

  NodePtr d_;
  PotentialPtr P_;
  std::unique_ptr<RadiusProfile> T_;
  WSource src_;
  double w_ = 1;
  NodePtr f_;
  double scale_ = 1, w_min_ = 1e-4;
  Box support_;  // region(0+, Above): the field is 0 outside
};

// T_a*, T_s* and contour: w from the modulation (or contour) node `key` (docs/math.md §4.5-§4.8).
NodePtr create_modulated(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx,
                         std::unique_ptr<RadiusProfile> profile, WSource src, const char* key,
                         double scale) {
  const double w_min = r.number("w_min", 1e-4);
  check_same_skeleton(r, key, ctx);
  NodePtr f = build_node(r, key, ctx);
  const FieldNode &dn = *d, &fn = *f;
  NodePtr node = std::make_unique<TransformedSoftObject>(
      std::move(d), std::move(P), std::move(profile), src, std::move(f), scale, w_min);
  check_modulation_side(r, key, *node, dn, fn, scale, src == WSource::Outer, ctx);
  return node;
}

}  // namespace

NodePtr create_T_n(const Params& r, NodePtr d, PotentialPtr P, const BuildContext&) {
  const double w1 = r.number("w1"), w2 = r.number("w2");
  r.check(w2 <= 2 * w1, "w2", "expected w2 <= 2*w1, else T_n is not monotone (docs/math.md §4.2)");
  return std::make_unique<TransformedSoftObject>(std::move(d), std::move(P),
                                                 make_profile_n(W2Rule::Fixed, w2), w1);
}
NodePtr create_T_l(const Params& r, NodePtr d, PotentialPtr P, const BuildContext&) {
  return std::make_unique<TransformedSoftObject>(std::move(d), std::move(P), make_profile_l(),
                                                 r.number("w1"));
}
NodePtr create_T_r(const Params& r, NodePtr d, PotentialPtr P, const BuildContext&) {
  return std::make_unique<TransformedSoftObject>(std::move(d), std::move(P), make_profile_r(),
                                                 r.number("w2"));
}
NodePtr create_T_an(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_n(W2Rule::Double),
                          WSource::Outer, "modulation", 1);
}
NodePtr create_T_al(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_l(), WSource::Outer,
                          "modulation", 1);
}
NodePtr create_T_sn(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_n(W2Rule::Equal),
                          WSource::Inner, "modulation", 1);
}
NodePtr create_T_sr(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_r(), WSource::Inner,
                          "modulation", 1);
}
// [000]'s contour surface fc = 1 is T_an with f_a = fc/2 (docs/math.md §4.8, [VIR-2]).
NodePtr create_contour(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx) {
  return create_modulated(r, std::move(d), std::move(P), ctx, make_profile_n(W2Rule::Double),
                          WSource::Outer, "contour", 0.5);
}

NodePtr create_soft_object(const Params& p, const BuildContext& ctx) {
  NodePtr d = build_node(p, "distance", ctx);
  PotentialPtr P = p.has("potential") ? build_potential(p.object("potential")) : make_blanc(0);
  if (!p.has("radii")) return std::make_unique<SoftObject>(std::move(d), std::move(P));
  BuildContext inner = ctx;
  inner.skeleton = skeleton_of(p.raw().at("distance"));
  return build_radius_transform(p.object("radii"), std::move(d), std::move(P), inner);
}

}  // namespace softtrace

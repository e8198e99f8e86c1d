// Distances in cylindrical coordinates (ρ, φ, z) about the z axis: the torus (circle skeleton)
// and the polar prism whose cross-section radius R(φ) is docs/math.md §10.1's rose or star.
#include <cmath>

#include "describe/distance_params.h"
#include "kernels/gauge.h"
#include "kernels/polar_prism.h"
#include "kernels/skeletal.h"
#include "model/distances.h"
#include "model/program_builder.h"
#include "program/ops/skeletal_ops.h"

namespace softtrace {

namespace {

// ((|ρ - R|/a)^n + (|z|/b)^n)^(1/n)   — docs/scene-format.md torus: the LP gauge of §2.5 in the (ρ,
// z) plane, ray-linear about the nearest point of the circle skeleton (docs/math.md §2.1). Bounds:
// |∇ρ| = 1 and ∇ρ ⟂ z, so ∇f has orthogonal parts ∂_1/a and ∂_2/b: the 2-D gauge's
// gauge_lipschitz(1/a, 1/b) globally, partial bounds from (ρ, z) intervals over a box. The
// kernels: skeletal.h.
class Torus final : public FieldNode {
 public:
  Torus(double R, double a, double b, double n) : m_{R, a, b, n, 0} {
    const double w[2] = {1 / a, 1 / b};
    m_.global_L = gauge_lipschitz(w, 2, n);
  }

  double eval(const Vec3& p, Vec3* grad) const override { return torus(m_, p, grad); }
  double lipschitz() const override { return m_.global_L; }
  // f <= c forces |ρ - R| <= c·a and |z| <= c·b (a power sum is at least its largest term).
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    const double r = (m_.R + level * m_.a) * (1 + 1e-12), h = level * m_.b * (1 + 1e-12);
    return {{-r, -r, -h}, {r, r, h}};
  }
  // One instruction with the parameters inline, in TorusOp's layout.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{Op::Torus};
    i.in = reg;
    i.out = b.new_slot();
    i.a = b.consts(TorusOp::constants(m_));
    return b.emit(i);
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    NodeBounds out;
    torus_bounds(m_, b, &out.value, &out.lipschitz);
    return out;
  }

  TorusParams m_;
};

// (h^n + |z/c|^n)^(1/n), h = ρ/R(φ)   — docs/math.md §10.1's substitutes for [000] Fig. 13's rose
// bar and star contour. The kernels and why their bounds hold: polar_prism.h.
class PolarPrism final : public FieldNode {
 public:
  PolarPrism(double r0, int k, double A, PolarProfile kind, double c, double n)
      : m_(polar_prism_params(r0, k, A, kind, c, n)) {}

  double eval(const Vec3& p, Vec3* grad) const override { return polar_prism(m_, p, grad); }
  double lipschitz() const override { return m_.global; }
  // f <= c forces h <= c, so ρ <= c·Rmax = c·r0 (1 + A), and |z| <= c·c_z.
  Box region(double level, Side side) const override {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    const double r = level * m_.r0 * (1 + m_.A) * (1 + 1e-12), h = level * m_.c * (1 + 1e-12);
    return {{-r, -r, -h}, {r, r, h}};
  }
  // One instruction with the parameters inline, in PolarPrismOp's layout.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{Op::PolarPrism};
    i.in = reg;
    i.out = b.new_slot();
    i.a = b.consts(PolarPrismOp::constants(m_));
    return b.emit(i);
  }

 private:
  NodeBounds box_bounds(const Box& b) const override {
    NodeBounds out;
    polar_prism_bounds(m_, b, &out.value, &out.lipschitz);
    return out;
  }

  PolarPrismParams m_;
};

}  // namespace

NodePtr create_torus(const Params& p, const BuildContext&) {
  const std::vector<double> r = p.numbers("radii");  // [a, b]
  return std::make_unique<Torus>(p.number("major_radius"), r[0], r[1], p.number("n", 2));
}

NodePtr create_polar_prism(const Params& p, const BuildContext&) {
  const double r0 = p.number("radius");
  const int k = p.integer("lobes", 1, 1000);
  const double A = p.number("amplitude");  // 0 <= A < 1 (the table): R(φ) > 0
  const std::string name = p.string("profile");
  const PolarProfile kind = name == "cosine" ? PolarProfile::Cosine : PolarProfile::Triangle;
  return std::make_unique<PolarPrism>(r0, k, A, kind, p.number("half_height"), p.number("n", 20));
}

}  // namespace softtrace

// Distances in cylindrical coordinates (ρ, φ, z) about the z axis: the torus (circle skeleton)
// and the polar prism whose cross-section radius R(φ) is docs/math.md §10.1's rose or star.
#include <cmath>

#include "describe/distance_params.h"
#include "kernels/gauge.h"
#include "kernels/polar_prism.h"
#include "kernels/skeletal.h"
#include "model/distances.h"
#include "model/kernel_node.h"
#include "model/program_builder.h"
#include "program/ops/skeletal_ops.h"

namespace softtrace {

namespace {

// ((|ρ - R|/a)^n + (|z|/b)^n)^(1/n)   — docs/scene-format.md torus: the LP gauge of §2.5 in the (ρ,
// z) plane, ray-linear about the nearest point of the circle skeleton (docs/math.md §2.1). Bounds:
// |∇ρ| = 1 and ∇ρ ⟂ z, so ∇f has orthogonal parts ∂_1/a and ∂_2/b: the 2-D gauge's
// gauge_lipschitz(1/a, 1/b) globally, partial bounds from (ρ, z) intervals over a box. The
// kernels: skeletal.h. Its node is KernelNode<Torus>.
struct Torus : KernelOf<TorusParams, TorusOp, Op::Torus, torus, torus_bounds> {
  static TorusParams params(double R, double a, double b, double n) {
    const double w[2] = {1 / a, 1 / b};
    return {R, a, b, n, gauge_lipschitz(w, 2, n)};
  }
  static double value(const TorusParams& m, const Vec3& p, Vec3* grad) { return torus(m, p, grad); }
  static void bounds(const TorusParams& m, const Box& b, Interval* value, double* lipschitz) {
    torus_bounds(m, b, value, lipschitz);
  }
  static double lipschitz(const TorusParams& m) { return m.global_L; }
  // f <= c forces |ρ - R| <= c·a and |z| <= c·b (a power sum is at least its largest term).
  static Box region(const TorusParams& m, double level, Side side) {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    const double r = (m.R + level * m.a) * (1 + 1e-12), h = level * m.b * (1 + 1e-12);
    return {{-r, -r, -h}, {r, r, h}};
  }
};

// (h^n + |z/c|^n)^(1/n), h = ρ/R(φ)   — docs/math.md §10.1's substitutes for [000] Fig. 13's rose
// bar and star contour. The kernels and why their bounds hold: polar_prism.h. Its node is
// KernelNode<PolarPrism>.
struct PolarPrism
    : KernelOf<PolarPrismParams, PolarPrismOp, Op::PolarPrism, polar_prism, polar_prism_bounds> {
  static double lipschitz(const PolarPrismParams& m) { return m.global; }
  // f <= c forces h <= c, so ρ <= c·Rmax = c·r0 (1 + A), and |z| <= c·c_z.
  static Box region(const PolarPrismParams& m, double level, Side side) {
    if (side == Side::Above) return Box::unbounded();
    if (level < 0) return Box();
    const double r = level * m.r0 * (1 + m.A) * (1 + 1e-12), h = level * m.c * (1 + 1e-12);
    return {{-r, -r, -h}, {r, r, h}};
  }
};

}  // namespace

NodePtr create_torus(const Params& p, const BuildContext&) {
  const std::vector<double> r = p.numbers("radii");  // [a, b]
  return std::make_unique<KernelNode<Torus>>(
      Torus::params(p.number("major_radius"), r[0], r[1], p.number("n", 2)));
}

NodePtr create_polar_prism(const Params& p, const BuildContext&) {
  const double r0 = p.number("radius");
  const int k = p.integer("lobes", 1, 1000);
  const double A = p.number("amplitude");  // 0 <= A < 1 (the table): R(φ) > 0
  const std::string name = p.string("profile");
  const PolarProfile kind = name == "cosine" ? PolarProfile::Cosine : PolarProfile::Triangle;
  return std::make_unique<KernelNode<PolarPrism>>(
      polar_prism_params(r0, k, A, kind, p.number("half_height"), p.number("n", 20)));
}

}  // namespace softtrace

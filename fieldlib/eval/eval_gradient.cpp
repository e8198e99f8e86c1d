// f and ∇f at one point, forward mode: every slot carries its value and its gradient with respect
// to the world point, and every point register carries its Jacobian with respect to the world
// point, so an oracle's local gradient g becomes Jᵀg.
#include "eval/eval.h"
#include "kernels/complement.h"
#include "kernels/generalized_distance.h"
#include "kernels/lp_metric.h"
#include "kernels/offset.h"
#include "kernels/perlin.h"
#include "kernels/planes.h"
#include "kernels/polar_prism.h"
#include "kernels/potentials.h"
#include "kernels/ricci.h"
#include "kernels/skeletal.h"
#include "kernels/spherical_product.h"
#include "kernels/strength.h"
#include "kernels/super_ellipsoidal.h"
#include "kernels/transformed_potential.h"
#include "math/scratch.h"

namespace softtrace {

namespace {
Mat3 times(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C.r[i][j] = A.r[i][0] * B.r[0][j] + A.r[i][1] * B.r[1][j] + A.r[i][2] * B.r[2][j];
  return C;
}

// A potential's value and slope applied to the distance's dual number (P' = 0 gives a zero
// gradient even where ∇d is infinite).
Workspace::Dual chain(double v, double dP, const Workspace::Dual& d) {
  return {v, dP == 0 ? Vec3{} : d.g * dP};
}
}  // namespace

namespace {
// f and ∇f over c.code[begin, end). With `kept` (c a whole program), a sum skips the children
// whose support boxes miss the point, as value_pruned does (eval_values.cpp): the value and
// gradient of the program pruned to the point, without building that view.
void gradient_range(const Code& c, int begin, int end, Workspace::Dual* S, Workspace::Frame* R,
                    int32_t* kept);

// The group of sum `g` so: its kept children, then their sum in the view's order. Returns the
// index after the sum.
int gradient_sum(const Code& c, const Group& g, Workspace::Dual* S, Workspace::Frame* R,
                 int32_t* kept) {
  const int n = g.kept_at(R[g.reg].p, kept);
  Workspace::Dual s{0, {}};
  for (int j = 0; j < n; ++j) {
    const Group::Child& child = g.children[kept[j]];
    gradient_range(c, child.begin, child.end, S, R, kept + n);
    s.v += S[child.slot].v;
    s.g += S[child.slot].g;
  }
  S[c.code[g.op_index].out] = s;
  return g.op_index + 1;
}

void gradient_range(const Code& c, int begin, int end, Workspace::Dual* S, Workspace::Frame* R,
                    int32_t* kept) {
  const double* K = c.base->consts.data();
  // A kernel of the point register in.in: its value, and its local gradient pulled back to the
  // world point (Jᵀg; passed unchanged where J = I, so an infinite gradient meets no 0·inf).
  const auto local = [&](const Instr& in, const auto& kernel) {
    const Workspace::Frame& f = R[in.in];
    Vec3 g;
    const double v = kernel(f.p, &g);
    S[in.out] = {v, f.identity ? g : f.J.transposed_times(g)};
  };
  // An n-ary instruction's children's values and gradients, for kernels that take them as arrays.
  const auto gather = [&](const Instr& in, double* x, Vec3* g) {
    for (int j = 0; j < in.n; ++j) {
      x[j] = S[c.args[in.a + j]].v;
      g[j] = S[c.args[in.a + j]].g;
    }
  };

  for (int k = begin; k < end; ++k) {
    const Instr& in = c.code[k];
    switch (in.op) {
      case Op::Translate: {
        const double* t = K + in.a;
        const Workspace::Frame& f = R[in.in];
        R[in.out] = {{f.p.x - t[0], f.p.y - t[1], f.p.z - t[2]}, f.J, f.identity};
        break;
      }
      case Op::Place: {
        const double* t = K + in.a;
        Mat3 Rt;
        for (int i = 0; i < 3; ++i) Rt.r[i] = {t[3 + 3 * i], t[4 + 3 * i], t[5 + 3 * i]};
        const Workspace::Frame& f = R[in.in];
        R[in.out] = {Rt * (f.p - Vec3{t[0], t[1], t[2]}), f.identity ? Rt : times(Rt, f.J), false};
        break;
      }
      case Op::Oracle:
        local(in, [&](const Vec3& q, Vec3* g) { return in.node->eval(q, g); });
        break;
      case Op::LpMetric: {
        const double* k = K + in.a;
        local(in, [&](const Vec3& q, Vec3* g) { return lp_metric(LpMetricParams::load(k), q, g); });
        break;
      }
      case Op::SphericalProduct:
        local(in, [&](const Vec3& q, Vec3* g) {
          return spherical_product(spherical_product_params(K + in.a), q, g);
        });
        break;
      case Op::ParallelPlanes:
        local(in, [&](const Vec3& q, Vec3* g) {
          return parallel_planes(plane_params(K + in.a), q, g);
        });
        break;
      case Op::OneBranchPlane:
        local(in, [&](const Vec3& q, Vec3* g) {
          return one_branch_plane(plane_params(K + in.a), q, g);
        });
        break;
      case Op::LineSegment:
        local(in, [&](const Vec3& q, Vec3* g) {
          return line_segment_distance(line_segment_params(K + in.a), q, g);
        });
        break;
      case Op::Torus:
        local(in, [&](const Vec3& q, Vec3* g) { return torus(torus_params(K + in.a), q, g); });
        break;
      case Op::GenDistance:
        local(in, [&](const Vec3& q, Vec3* g) {
          return generalized_distance({K + in.a, in.n}, q, g);
        });
        break;
      case Op::PolarPrism:
        local(in, [&](const Vec3& q, Vec3* g) {
          return polar_prism(polar_prism_params(K + in.a), q, g);
        });
        break;
      case Op::Blanc: {
        double dP;
        const double v = blanc(S[in.in].v, K[in.a], &dP);
        S[in.out] = chain(v, dP, S[in.in]);
        break;
      }
      case Op::Wyvill: {
        double dP;
        const double v = wyvill(S[in.in].v, &dP);
        S[in.out] = chain(v, dP, S[in.in]);
        break;
      }
      case Op::Murakami: {
        double dP;
        const double v = murakami(S[in.in].v, &dP);
        S[in.out] = chain(v, dP, S[in.in]);
        break;
      }
      case Op::Cubic: {
        double dP;
        const double v = cubic(S[in.in].v, &dP);
        S[in.out] = chain(v, dP, S[in.in]);
        break;
      }
      case Op::Strength: {
        const Workspace::Dual& d = S[in.in];
        S[in.out] = {strength_value(K[in.a], d.v), strength_gradient(K[in.a], d.g)};
        break;
      }
      case Op::Offset: {
        const Workspace::Dual& d = S[in.in];
        S[in.out] = {offset_value(K[in.a], K[in.a + 1], d.v), offset_gradient(K[in.a], d.g)};
        break;
      }
      case Op::Complement: {
        Workspace::Dual d = S[in.in];
        d.v = complement(complement_convention(K + in.a), d.v, &d.g);
        S[in.out] = d;
        break;
      }
      case Op::RadiusTransform: {
        const Workspace::Dual &d = S[in.in], &f = S[in.n];
        Workspace::Dual r;
        r.v = TransformedPotential::load(K + in.a).eval(d.v, d.g, f.v, f.g, &r.g);
        S[in.out] = r;
        break;
      }
      case Op::Group: {
        const Group& g = c.base->groups[in.a];
        if (kept && !g.bvh.empty()) k = gradient_sum(c, g, S, R, kept) - 1;
        break;
      }
      case Op::Sum: {
        Workspace::Dual s{0, {}};
        for (int j = 0; j < in.n; ++j) {
          const Workspace::Dual& a = S[c.args[in.a + j]];
          s.v += a.v;
          s.g += a.g;
        }
        S[in.out] = s;
        break;
      }
      case Op::Min:
      case Op::Max: {
        const bool is_min = in.op == Op::Min;
        Workspace::Dual best = S[c.args[in.a]];
        for (int j = 1; j < in.n; ++j) {
          const Workspace::Dual& a = S[c.args[in.a + j]];
          if (is_min ? a.v < best.v : a.v > best.v) best = a;
        }
        S[in.out] = best;
        break;
      }
      case Op::SuperUnion:
      case Op::SuperIntersect: {
        // The kernels on the children's values and gradients gathered.
        const size_t k = in.n;
        const double e = K[in.in];
        Scratch<double> x(k);
        Scratch<Vec3> g(k);
        gather(in, x.data(), g.data());
        Workspace::Dual d;
        if (in.op == Op::SuperUnion) {
          d.v = super_union(x.data(), k, e);
          d.g = super_union_gradient(x.data(), g.data(), k, e, d.v);
        } else {
          d.v = super_intersection(x.data(), g.data(), k, e, &d.g);
        }
        S[in.out] = d;
        break;
      }
      case Op::Perlin: {
        const size_t k = in.n;
        Scratch<double> x(k);
        Scratch<Vec3> g(k);
        gather(in, x.data(), g.data());
        Workspace::Dual d;
        d.v = perlin(perlin_mode(K + in.in), x.data(), g.data(), k, &d.g);
        S[in.out] = d;
        break;
      }
      case Op::Ricci: {
        const size_t k = in.n;
        Scratch<double> x(k);
        Scratch<Vec3> g(k);
        gather(in, x.data(), g.data());
        Workspace::Dual d;
        d.v = ricci(ricci_params(K + in.in), x.data(), g.data(), k, &d.g);
        S[in.out] = d;
        break;
      }
    }
  }
}
}  // namespace

double gradient(Code c, const Vec3& p, Vec3* grad, Workspace& ws) {
  ws.frames[0] = {p, Mat3{}, true};
  gradient_range(c, 0, c.size, ws.duals.data(), ws.frames.data(), nullptr);
  if (grad) *grad = ws.duals[c.result].g;
  return ws.duals[c.result].v;
}

double gradient_pruned(const Program& p, const Vec3& point, Vec3* grad, Workspace& ws) {
  ws.frames[0] = {point, Mat3{}, true};
  gradient_range(p, 0, static_cast<int>(p.code.size()), ws.duals.data(), ws.frames.data(),
                 ws.kept.data());
  if (grad) *grad = ws.duals[p.result].g;
  return ws.duals[p.result].v;
}

}  // namespace softtrace

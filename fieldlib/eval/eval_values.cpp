// Values at a batch of points: each instruction runs over every lane before the next, so the
// kernels are loops over contiguous doubles that the compiler can vectorise, and an oracle pays
// its virtual call per lane only for its own subtree.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "eval/eval.h"
#include "kernels/complement.h"
#include "kernels/gauge.h"
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
// A super-ellipsoidal, Perlin or Ricci combination of its children's values x[0..in.n), gathered
// by the caller into scratch the kernels work in.
double combination(const Instr& in, const double* K, double* x) {
  const size_t k = in.n;
  switch (in.op) {
    case Op::SuperUnion:
      return super_union(x, k, K[in.in]);
    case Op::SuperIntersect:
      return super_intersection(x, nullptr, k, K[in.in], nullptr);
    case Op::Ricci:
      return ricci(ricci_params(K + in.in), x, nullptr, k, nullptr);
    case Op::Perlin:
      return perlin(perlin_mode(K + in.in), x, nullptr, k, nullptr);
    default:
      std::abort();  // only the four combinations reach here: no other op's maths by default
  }
}
}  // namespace

void values(Code c, const double* x, const double* y, const double* z, int n, double* f,
            Workspace& ws) {
  double* S = ws.slots.data();
  double* R = ws.regs.data();
  const double* K = c.base->consts.data();
  const auto reg = [&](int r, int axis) { return R + (r * 3 + axis) * kBatch; };
  std::copy(x, x + n, reg(0, 0));
  std::copy(y, y + n, reg(0, 1));
  std::copy(z, z + n, reg(0, 2));

  for (int k = 0; k < c.size; ++k) {
    const Instr& in = c.code[k];
    double* out = S + in.out * kBatch;
    switch (in.op) {
      case Op::Translate: {
        const double* t = K + in.a;
        for (int i = 0; i < 3; ++i) {
          const double* src = reg(in.in, i);
          double* dst = reg(in.out, i);
          for (int l = 0; l < n; ++l) dst[l] = src[l] - t[i];
        }
        break;
      }
      case Op::Place: {
        const double* t = K + in.a;
        const double* M = t + 3;
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        double *qx = reg(in.out, 0), *qy = reg(in.out, 1), *qz = reg(in.out, 2);
        for (int l = 0; l < n; ++l) {
          const double u = px[l] - t[0], v = py[l] - t[1], w = pz[l] - t[2];
          qx[l] = M[0] * u + M[1] * v + M[2] * w;
          qy[l] = M[3] * u + M[4] * v + M[5] * w;
          qz[l] = M[6] * u + M[7] * v + M[8] * w;
        }
        break;
      }
      case Op::Oracle: {
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        for (int l = 0; l < n; ++l) out[l] = in.node->eval({px[l], py[l], pz[l]}, nullptr);
        break;
      }
      case Op::LpMetric: {
        const double* k = K + in.a;
        const LpMetricParams m = LpMetricParams::load(k);
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        if (m.n != 2) {
          // lp_metric's general path: the terms |p_i / a_i|, then the power sum over the lanes.
          double u[3][kBatch];
          for (int l = 0; l < n; ++l) {
            u[0][l] = std::abs(px[l] / k[0]);
            u[1][l] = std::abs(py[l] / k[1]);
            u[2][l] = std::abs(pz[l] / k[2]);
          }
          const double* rows[3] = {u[0], u[1], u[2]};
          power_sum_lanes(rows, 3, m.n, n, out);
          break;
        }
        // lp_metric's n = 2 path as a branch-free loop over the lanes (it vectorises), then the
        // kernel itself for the rare lanes outside its range.
        for (int l = 0; l < n; ++l) {
          const double x = px[l] / k[0], y = py[l] / k[1], z = pz[l] / k[2];
          out[l] = x * x + y * y + z * z;
        }
        for (int l = 0; l < n; ++l)
          out[l] = out[l] > 1e-280 && out[l] < 1e280 ? std::sqrt(out[l])
                                                     : lp_metric(m, {px[l], py[l], pz[l]}, nullptr);
        break;
      }
      case Op::SphericalProduct: {
        const SphericalProductParams m = spherical_product_params(K + in.a);
        // OneSidedTerm::value over the lanes as plain selects on locals, a loop GCC vectorises
        // (not with nested selects, nor with the parameters read through m): at most one of
        // s - L and -s - L is positive, so one quotient; 0/1 where neither is (NaN s included).
        double u[3][kBatch], h[kBatch];
        for (int i = 0; i < 3; ++i) {
          const double dead = m.t[i].dead, r_pos = m.t[i].r_pos, r_neg = m.t[i].r_neg;
          const double* s = reg(in.in, i);
          for (int l = 0; l < n; ++l) {
            const double a = s[l] - dead, b = -s[l] - dead;
            const double nb = b > 0 ? b : 0.0, rb = b > 0 ? r_neg : 1.0;
            u[i][l] = (a > 0 ? a : nb) / (a > 0 ? r_pos : rb);
          }
        }
        const double* inner[2] = {u[0], u[1]};
        power_sum_lanes(inner, 2, m.n1, n, h);
        const double* outer[2] = {h, u[2]};
        power_sum_lanes(outer, 2, m.n2, n, out);
        break;
      }
      case Op::ParallelPlanes:
      case Op::OneBranchPlane: {
        // The kernels' dot(p, n) and quotient over the lanes, with the parameters in locals (a loop
        // GCC vectorises); std::max keeps the kernel's answer for NaN and -0.
        const double nx = K[in.a], ny = K[in.a + 1], nz = K[in.a + 2], a = K[in.a + 3];
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        if (in.op == Op::ParallelPlanes) {
          for (int l = 0; l < n; ++l) out[l] = std::abs(px[l] * nx + py[l] * ny + pz[l] * nz) / a;
        } else {
          for (int l = 0; l < n; ++l)
            out[l] = std::max(px[l] * nx + py[l] * ny + pz[l] * nz, 0.0) / a;
        }
        break;
      }
      case Op::LineSegment: {
        // line_segment_distance over the lanes with the parameters in locals: the squared distances
        // in a loop GCC vectorises, then the roots (scalar: std::sqrt may set errno).
        const LineSegmentParams m = line_segment_params(K + in.a);
        const double ax = m.a.x, ay = m.a.y, az = m.a.z, bx = m.ab.x, by = m.ab.y, bz = m.ab.z;
        const double len2 = m.len2;
        const bool along = len2 > 0;
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        for (int l = 0; l < n; ++l) {
          const double w = (px[l] - ax) * bx + (py[l] - ay) * by + (pz[l] - az) * bz;
          const double t = along ? std::clamp(w / len2, 0.0, 1.0) : 0.0;
          const double qx = px[l] - (ax + bx * t), qy = py[l] - (ay + by * t),
                       qz = pz[l] - (az + bz * t);
          out[l] = qx * qx + qy * qy + qz * qz;
        }
        for (int l = 0; l < n; ++l) out[l] = std::sqrt(out[l]) / m.r;
        break;
      }
      case Op::Torus: {
        // torus's terms lane by lane (hypot is a libm call), then power_sum_lanes.
        const TorusParams m = torus_params(K + in.a);
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        double u[2][kBatch];
        for (int l = 0; l < n; ++l) {
          u[0][l] = std::abs(std::hypot(px[l], py[l]) - m.R) / m.a;
          u[1][l] = std::abs(pz[l]) / m.b;
        }
        const double* rows[2] = {u[0], u[1]};
        power_sum_lanes(rows, 2, m.n, n, out);
        break;
      }
      case Op::GenDistance: {
        // The one-sided terms of X·n_i over the lanes as SphericalProduct's selects (a loop GCC
        // vectorises), one row per normal, then power_sum_lanes over the rows.
        const GeneralizedDistanceParams m{K + in.a, in.n};
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        Scratch<double, 16 * kBatch> u(size_t(m.k) * kBatch);
        Scratch<const double*> rows(m.k);
        for (int i = 0; i < m.k; ++i) {
          const double* t = m.c + kGdHeader + kGdStride * i;
          const double nx = t[0], ny = t[1], nz = t[2], r_pos = t[3], r_neg = t[4], dead = t[5];
          double* ui = u.data() + i * kBatch;
          for (int l = 0; l < n; ++l) {
            const double s = px[l] * nx + py[l] * ny + pz[l] * nz;
            const double a = s - dead, b = -s - dead;
            const double nb = b > 0 ? b : 0.0, rb = b > 0 ? r_neg : 1.0;
            ui[l] = (a > 0 ? a : nb) / (a > 0 ? r_pos : rb);
          }
          rows[i] = ui;
        }
        power_sum_lanes(rows.data(), m.k, m.n(), n, out);
        break;
      }
      case Op::PolarPrism: {
        // polar_prism's terms lane by lane (hypot, atan2 and the profile are libm calls), then
        // power_sum_lanes.
        const PolarPrismParams m = polar_prism_params(K + in.a);
        const double *px = reg(in.in, 0), *py = reg(in.in, 1), *pz = reg(in.in, 2);
        double u[2][kBatch];
        for (int l = 0; l < n; ++l) {
          u[0][l] = std::hypot(px[l], py[l]) / polar_prism_radius(m, px[l], py[l], nullptr);
          u[1][l] = std::abs(pz[l]) / m.c;
        }
        const double* rows[2] = {u[0], u[1]};
        power_sum_lanes(rows, 2, m.n, n, out);
        break;
      }
      case Op::Blanc: {
        const double* d = S + in.in * kBatch;
        const double s = K[in.a];
        blanc_lanes(d, s, n, out);
        break;
      }
      case Op::Wyvill: {
        const double* d = S + in.in * kBatch;
        for (int l = 0; l < n; ++l) out[l] = wyvill(d[l], nullptr);
        break;
      }
      case Op::Murakami: {
        const double* d = S + in.in * kBatch;
        for (int l = 0; l < n; ++l) out[l] = murakami(d[l], nullptr);
        break;
      }
      case Op::Cubic: {
        const double* d = S + in.in * kBatch;
        for (int l = 0; l < n; ++l) out[l] = cubic(d[l], nullptr);
        break;
      }
      case Op::Strength: {
        const double* d = S + in.in * kBatch;
        const double s = K[in.a];
        for (int l = 0; l < n; ++l) out[l] = strength_value(s, d[l]);
        break;
      }
      case Op::Offset: {
        const double* d = S + in.in * kBatch;
        const double sc = K[in.a], lv = K[in.a + 1];
        for (int l = 0; l < n; ++l) out[l] = offset_value(sc, lv, d[l]);
        break;
      }
      case Op::Complement: {
        // The kernel's three forms as loops over the lanes (the guarded 1/f as a select).
        const double* d = S + in.in * kBatch;
        switch (complement_convention(K + in.a)) {
          case Convention::Soft:
            for (int l = 0; l < n; ++l) out[l] = 1 - d[l];
            break;
          case Convention::Zero:
            for (int l = 0; l < n; ++l) out[l] = -d[l];
            break;
          case Convention::Constructive:
            for (int l = 0; l < n; ++l) out[l] = 1 / (d[l] <= kCgFloor ? kCgFloor : d[l]);
            break;
        }
        break;
      }
      case Op::RadiusTransform: {
        // The shared kernel lane by lane (T and P are branches and libm calls).
        const TransformedPotential t = TransformedPotential::load(K + in.a);
        const double* d = S + in.in * kBatch;
        const double* f = S + in.n * kBatch;
        const Vec3 none;
        for (int l = 0; l < n; ++l) out[l] = t.eval(d[l], none, f[l], none, nullptr);
        break;
      }
      case Op::Group:
        break;
      case Op::Sum: {
        std::fill(out, out + n, 0.0);
        for (int j = 0; j < in.n; ++j) {
          const double* a = S + c.args[in.a + j] * kBatch;
          for (int l = 0; l < n; ++l) out[l] += a[l];
        }
        break;
      }
      case Op::Min:
      case Op::Max: {
        // The first extreme in child order wins ties, as the model's min/max does.
        const bool is_min = in.op == Op::Min;
        const double* a0 = S + c.args[in.a] * kBatch;
        std::copy(a0, a0 + n, out);
        for (int j = 1; j < in.n; ++j) {
          const double* a = S + c.args[in.a + j] * kBatch;
          for (int l = 0; l < n; ++l)
            if (is_min ? a[l] < out[l] : a[l] > out[l]) out[l] = a[l];
        }
        break;
      }
      case Op::SuperUnion:
      case Op::SuperIntersect:
      case Op::Perlin:
      case Op::Ricci: {
        // The kernels lane by lane (pow is a libm call), on the children's values gathered.
        Scratch<double> x(in.n);
        for (int l = 0; l < n; ++l) {
          for (int j = 0; j < in.n; ++j) x[j] = S[c.args[in.a + j] * kBatch + l];
          out[l] = combination(in, K, x.data());
        }
        break;
      }
    }
  }
  std::copy(S + c.result * kBatch, S + c.result * kBatch + n, f);
}

namespace {
// One point over c.code[begin, end): the same operations as one lane of `values` (so the same
// bits), without the lane loops, whose set-up costs more than the work for a single point (the
// tracer's case). With `kept` (room for the program's children; c a whole program, not a view),
// a sum whose children have support boxes evaluates only those whose boxes hold the point, as
// the program pruned to the point would (the others are exactly 0 there) without building it.
void point_range(const Code& c, int begin, int end, double* S, Vec3* R, int32_t* kept);

// The group of sum `g` so: its kept children, then their sum in the view's order. Returns the
// index after the sum.
int point_sum(const Code& c, const Group& g, double* S, Vec3* R, int32_t* kept) {
  const int n = g.kept_at(R[g.reg], kept);
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    const Group::Child& child = g.children[kept[j]];
    point_range(c, child.begin, child.end, S, R, kept + n);
    sum += S[child.slot];
  }
  S[c.code[g.op_index].out] = sum;
  return g.op_index + 1;
}

void point_range(const Code& c, int begin, int end, double* S, Vec3* R, int32_t* kept) {
  const double* K = c.base->consts.data();
  for (int k = begin; k < end; ++k) {
    const Instr& in = c.code[k];
    double& out = S[in.out];
    switch (in.op) {
      case Op::Translate: {
        const double* t = K + in.a;
        const Vec3& q = R[in.in];
        R[in.out] = {q.x - t[0], q.y - t[1], q.z - t[2]};
        break;
      }
      case Op::Place: {
        const double* t = K + in.a;
        const double* M = t + 3;
        const Vec3& q = R[in.in];
        const double u = q.x - t[0], v = q.y - t[1], w = q.z - t[2];
        R[in.out] = {M[0] * u + M[1] * v + M[2] * w, M[3] * u + M[4] * v + M[5] * w,
                     M[6] * u + M[7] * v + M[8] * w};
        break;
      }
      case Op::Oracle:
        out = in.node->eval(R[in.in], nullptr);
        break;
      case Op::LpMetric: {
        const double* k = K + in.a;
        out = lp_metric(LpMetricParams::load(k), R[in.in], nullptr);
        break;
      }
      case Op::SphericalProduct:
        out = spherical_product(spherical_product_params(K + in.a), R[in.in], nullptr);
        break;
      case Op::ParallelPlanes:
        out = parallel_planes(plane_params(K + in.a), R[in.in], nullptr);
        break;
      case Op::OneBranchPlane:
        out = one_branch_plane(plane_params(K + in.a), R[in.in], nullptr);
        break;
      case Op::LineSegment:
        out = line_segment_distance(line_segment_params(K + in.a), R[in.in], nullptr);
        break;
      case Op::Torus:
        out = torus(torus_params(K + in.a), R[in.in], nullptr);
        break;
      case Op::GenDistance:
        out = generalized_distance({K + in.a, in.n}, R[in.in], nullptr);
        break;
      case Op::PolarPrism:
        out = polar_prism(polar_prism_params(K + in.a), R[in.in], nullptr);
        break;
      case Op::Blanc:
        out = blanc(S[in.in], K[in.a], nullptr);
        break;
      case Op::Wyvill:
        out = wyvill(S[in.in], nullptr);
        break;
      case Op::Murakami:
        out = murakami(S[in.in], nullptr);
        break;
      case Op::Cubic:
        out = cubic(S[in.in], nullptr);
        break;
      case Op::Strength:
        out = strength_value(K[in.a], S[in.in]);
        break;
      case Op::Offset:
        out = offset_value(K[in.a], K[in.a + 1], S[in.in]);
        break;
      case Op::Complement:
        out = complement(complement_convention(K + in.a), S[in.in], nullptr);
        break;
      case Op::RadiusTransform: {
        const Vec3 none;
        out = TransformedPotential::load(K + in.a).eval(S[in.in], none, S[in.n], none, nullptr);
        break;
      }
      case Op::Group: {
        const Group& g = c.base->groups[in.a];
        if (kept && !g.bvh.empty()) k = point_sum(c, g, S, R, kept) - 1;
        break;
      }
      case Op::Sum: {
        double sum = 0;
        for (int j = 0; j < in.n; ++j) sum += S[c.args[in.a + j]];
        out = sum;
        break;
      }
      case Op::Min:
      case Op::Max: {
        const bool is_min = in.op == Op::Min;
        double e = S[c.args[in.a]];
        for (int j = 1; j < in.n; ++j) {
          const double a = S[c.args[in.a + j]];
          if (is_min ? a < e : a > e) e = a;
        }
        out = e;
        break;
      }
      case Op::SuperUnion:
      case Op::SuperIntersect:
      case Op::Perlin:
      case Op::Ricci: {
        Scratch<double> x(in.n);
        for (int j = 0; j < in.n; ++j) x[j] = S[c.args[in.a + j]];
        out = combination(in, K, x.data());
        break;
      }
    }
  }
}
}  // namespace

double value(Code c, const Vec3& p, Workspace& ws) {
  ws.points[0] = p;
  point_range(c, 0, c.size, ws.slots.data(), ws.points.data(), nullptr);
  return ws.slots[c.result];
}

double value_pruned(const Program& p, const Vec3& point, Workspace& ws) {
  ws.points[0] = point;
  point_range(p, 0, static_cast<int>(p.code.size()), ws.slots.data(), ws.points.data(),
              ws.kept.data());
  return ws.slots[p.result];
}

}  // namespace softtrace

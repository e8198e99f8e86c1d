#include "model/placement.h"

#include <algorithm>
#include <cmath>

#include "math/affine.h"
#include "model/program_builder.h"
#include "program/ops/placement_ops.h"

namespace softtrace {

namespace {

// The child's blob |L q + k| at q = M (x - t): |(L M) x + k - (L M) t|.
void compose(PolynomialBlob* b, const Mat3& M, const Vec3& t) {
  b->L = times(b->L, M);
  b->k = b->k - b->L * t;
}

Mat3 transpose(const Mat3& m) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.r[i][j] = m.r[j][i];
  return t;
}

class Placed final : public FieldNode {
 public:
  Placed(NodePtr child, const Mat3& R, const Vec3& t)
      : child_(std::move(child)),
        R_(R),
        Rt_(transpose(R)),
        t_(t),
        back_(Rt_ * (-t_)),
        rotated_(!is_identity(R)) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const double v = child_->eval(Rt_ * (p - t_), grad);
    if (grad) *grad = R_ * *grad;
    return v;
  }
  bool polynomial_blob(PolynomialBlob* b) const override {
    return child_->polynomial_blob(b) && (compose(b, Rt_, t_), true);
  }
  double lipschitz() const override { return child_->lipschitz(); }
  // A rigid motion keeps gradient lengths and Hessian norms.
  double gradient_floor(const Box& b) const override { return child_->gradient_floor(to_local(b)); }
  double hessian_bound(const Box& b) const override { return child_->hessian_bound(to_local(b)); }
  // H = R H_local R^T.
  bool hessian(const Vec3& p, Mat3* H) const override {
    Mat3 local;
    if (!child_->hessian(Rt_ * (p - t_), &local)) return false;
    *H = times(times(R_, local), Rt_);
    return true;
  }
  // A pure translation is three subtractions; a rotation one matrix.
  int compile(ProgramBuilder& b, int reg) const override {
    Instr i{rotated_ ? Op::Place : Op::Translate};
    i.in = reg;
    i.out = b.new_reg();
    i.a = rotated_ ? b.consts(PlaceOp::constants(t_, Rt_)) : b.consts(TranslateOp::constants(t_));
    b.emit(i);
    return b.compile(*child_, i.out);
  }
  Box region(double level, Side side) const override {
    const Box local = child_->region(level, side);
    if (!local.bounded()) return local;
    return rotated_ ? transform_box(local, R_, t_) : translate_box(local, R_, t_);
  }

 private:
  // A rigid motion keeps values and gradient lengths: the child's bounds over the box around b.
  NodeBounds box_bounds(const Box& b) const override { return child_->bounds(to_local(b)); }

  Box to_local(const Box& b) const {
    if (!b.bounded()) return Box::unbounded();
    return rotated_ ? transform_box(b, Rt_, back_) : translate_box(b, Rt_, back_);
  }

  static bool is_identity(const Mat3& m) {
    const Mat3 I;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (m.r[i][j] != I.r[i][j]) return false;
    return true;
  }

  NodePtr child_;
  Mat3 R_, Rt_;
  Vec3 t_;
  Vec3 back_;  // Rt_ (-t_): to_local's translation, the same expression as it once computed
  bool rotated_;
};

// The box around M (b - t) (centre through M, half extent through |M|), or around M b + t
// (`after`), padded by 1e-12 of the magnitudes that entered each coordinate: the few products
// and sums err by far less, and the subtraction first keeps a box far from the origin exact.
Box affine_box(const Box& b, const Mat3& M, const Vec3& t, bool after) {
  if (!b.bounded()) return Box::unbounded();
  const Vec3 c = after ? b.center() : b.center() - t, h = b.extent() * 0.5;
  Box o;
  for (int i = 0; i < 3; ++i) {
    const Vec3& m = M.r[i];
    const Vec3 am{std::abs(m.x), std::abs(m.y), std::abs(m.z)};
    const double shift = after ? t[i] : 0.0;
    const double ci = dot(m, c) + shift;
    const double hi = dot(am, h);
    const double pad = 1e-12 * (dot(am, Vec3{std::abs(c.x), std::abs(c.y), std::abs(c.z)}) +
                                std::abs(shift) + hi) +
                       1e-300;
    o.lo[i] = ci - hi - pad;
    o.hi[i] = ci + hi + pad;
  }
  return o;
}

// f(A^-1 (p - t)) for an invertible A   — docs/math.md §2.15
class AffinePlaced final : public FieldNode {
 public:
  AffinePlaced(NodePtr child, const Mat3& A, const Vec3& t)
      : child_(std::move(child)),
        A_(A),
        M_(inverse(A)),
        Mt_(transposed(M_)),
        t_(t),
        norm_M_(operator_norm_bound(M_)),
        floor_M_(std::max(0.0, iv::down(1 / operator_norm_bound(A)))) {}

  double eval(const Vec3& p, Vec3* grad) const override {
    const double v = child_->eval(M_ * (p - t_), grad);
    if (grad) *grad = Mt_ * *grad;  // ∇(f∘g) = M^T ∇f
    return v;
  }
  bool polynomial_blob(PolynomialBlob* b) const override {
    return child_->polynomial_blob(b) && (compose(b, M_, t_), true);
  }
  double lipschitz() const override { return scaled(child_->lipschitz()); }
  // |M^T g| >= σ_min(M) |g| = |g| / |A|_2; the Hessian is M^T H M, of norm <= |M|^2 |H|.
  double gradient_floor(const Box& b) const override {
    return std::max(0.0, iv::down(child_->gradient_floor(to_local(b)) * floor_M_));
  }
  double hessian_bound(const Box& b) const override {
    return iv::up(iv::up(child_->hessian_bound(to_local(b)) * norm_M_) * norm_M_);
  }
  bool hessian(const Vec3& p, Mat3* H) const override {
    Mat3 local;
    if (!child_->hessian(M_ * (p - t_), &local)) return false;
    *H = times(times(Mt_, local), M_);
    return true;
  }
  Box region(double level, Side side) const override {
    const Box local = child_->region(level, side);
    return local.bounded() ? affine_box(local, A_, t_, true) : local;
  }

 private:
  // The child's range over the box around M (b - t); its slopes times |M|_2 (∇(f∘g) = M^T ∇f).
  NodeBounds box_bounds(const Box& b) const override {
    const NodeBounds f = child_->bounds(to_local(b));
    return {f.value, scaled(f.lipschitz)};
  }

  Box to_local(const Box& b) const { return affine_box(b, M_, t_, false); }
  double scaled(double L) const { return L == 0 ? 0.0 : iv::up(L * norm_M_); }

  NodePtr child_;
  Mat3 A_, M_, Mt_;  // object to world, its inverse, and the inverse's transpose
  Vec3 t_;
  double norm_M_;   // >= |M|_2
  double floor_M_;  // <= σ_min(M) = 1 / |A|_2
};

}  // namespace

NodePtr place_affine(NodePtr child, const Mat3& A, const Vec3& t) {
  return std::make_unique<AffinePlaced>(std::move(child), A, t);
}

Box transform_box(const Box& b, const Mat3& R, const Vec3& t) {
  Box out;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                      (c & 4) ? b.hi.z : b.lo.z};
    out.extend(R * corner + t);
  }
  // Pad by a few ulps of the coordinates so rounding in R·p + t cannot drop a point.
  for (int i = 0; i < 3; ++i) {
    const double pad = 1e-12 * std::max(std::abs(out.lo[i]), std::abs(out.hi[i]));
    out.lo[i] -= pad;
    out.hi[i] += pad;
  }
  return out;
}

Box translate_box(const Box& b, const Mat3& I, const Vec3& t) {
  Box out;
  for (int i = 0; i < 3; ++i) {
    if (t[i] == 0 && (b.lo[i] == 0 || b.hi[i] == 0)) return transform_box(b, I, t);
    const double lo = b.lo[i] + t[i], hi = b.hi[i] + t[i];
    const double pad = 1e-12 * std::max(std::abs(lo), std::abs(hi));
    out.lo[i] = lo - pad;
    out.hi[i] = hi + pad;
  }
  return out;
}

NodePtr place(NodePtr child, const Mat3& rotation, const Vec3& translate) {
  return std::make_unique<Placed>(std::move(child), rotation, translate);
}

}  // namespace softtrace

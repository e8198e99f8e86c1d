// The one interface every field node answers (docs/math.md §8 for the bounds it promises).
// Models are built once from a scene and then only evaluated, from many threads at once:
// every method is const and thread-safe.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "math/box.h"
#include "math/convention.h"
#include "math/interval.h"
#include "math/vec.h"
#include "program/oracle.h"

namespace softtrace {

class ProgramBuilder;

class FieldNode : public Oracle {
 public:
  // f(p), and ∇f(p) into *grad when grad is non-null. Where f is not differentiable (kinks of
  // min/max, the skeleton of a gauge) any element of the Clarke subdifferential is acceptable.
  double eval(const Vec3& p, Vec3* grad) const override = 0;

  // A sound enclosure of f over the box. The default is f(centre) ± L(box)·half-diagonal, which
  // is sound for any node whose box Lipschitz bound is; nodes override it with tighter ones.
  virtual Interval interval(const Box& b) const;

  // Bounds on |∇f|: globally and over a box. +inf where no bound exists (exponents below 1).
  virtual double lipschitz() const = 0;
  virtual double lipschitz(const Box& b) const { return lipschitz(); }
  // interval(b) and lipschitz(b) together, equal to them bit for bit. Nodes whose two bounds
  // share their work (a gauge's terms; a modulated soft object's octant refinement) override it,
  // so that a caller needing both, as the bounds pass does for an oracle, pays for it once.
  void bounds(const Box& b, Interval* value, double* lipschitz) const override;

  // A box containing {p : f(p) >= level} (Side::Above) or {f(p) <= level} (Side::Below);
  // Box::unbounded() when no finite box is known. For soft fields, region(l, Above) with
  // l > 0 is the support box.
  virtual Box region(double level, Side side) const { return Box::unbounded(); }

  // For blends whose parameters follow the children's normals (bulge elimination, docs/math.md
  // §7.6): a lower bound on |∇f| over the box, and an upper bound on the Hessian's operator
  // norm there, i.e. a Lipschitz bound on ∇f, finite only where f is C^1 with no kink in the
  // box. The defaults claim nothing.
  virtual double gradient_floor(const Box& b) const { return 0; }
  virtual double hessian_bound(const Box& b) const {
    return std::numeric_limits<double>::infinity();
  }

  // Emits this node's subtree into a flat program (program.h), reading point register `reg`;
  // returns the slot of its value. The default is one oracle instruction that calls this node's
  // methods above; nodes with instructions of their own override it.
  virtual int compile(ProgramBuilder& b, int reg) const;

  double value(const Vec3& p) const { return eval(p, nullptr); }
  Vec3 gradient(const Vec3& p) const {
    Vec3 g;
    eval(p, &g);
    return g;
  }
};

using NodePtr = std::unique_ptr<FieldNode>;

}  // namespace softtrace

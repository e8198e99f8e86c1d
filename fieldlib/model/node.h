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

  // The box question: a sound enclosure of f over b and a bound on |∇f| there, answered together
  // by each kind (box_bounds below): most kinds derive both from the same terms, and a blend needs
  // both of every child, which it then asks once each. interval() and lipschitz(b) are its parts,
  // not separate questions; ask bounds() where both are needed.
  NodeBounds bounds(const Box& b) const { return box_bounds(b); }
  Interval interval(const Box& b) const { return box_bounds(b).value; }
  double lipschitz(const Box& b) const { return box_bounds(b).lipschitz; }

  // A different question: a bound on |∇f| over all of space, fixed when the node is built (the
  // tracer's step bound, and what the blends' global bounds and the program's constants are made
  // of). +inf where no bound exists (exponents below 1, surface-defined radii). Over a box,
  // lipschitz(b) is never above it.
  virtual double lipschitz() const = 0;

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
  // The exact Hessian of f at p into *H (symmetric, row-major), for the same blends' true
  // gradient (∇P_i and ∇M_i need ∇cosθ and ∇G, docs/math.md §7.6). False where the kind has no
  // closed form or f has no Hessian at p (a skeleton, a kink); the blend then differences the
  // gradient instead (blends_bt.h).
  virtual bool hessian(const Vec3& p, Mat3* H) const { return false; }

  // Emits this node's subtree into a flat program (program.h), reading point register `reg`;
  // returns the slot of its value. The default is one oracle instruction that calls this node's
  // methods above; nodes with instructions of their own override it.
  virtual int compile(ProgramBuilder& b, int reg) const;

  // A node equal to this one, for a blend's sibling built from the same parameters but its
  // placement (a cloud of equal blobs: registry.cpp copies the first instead of building each
  // again); null for the kinds that make no copy, whose siblings are each built in full.
  virtual std::unique_ptr<FieldNode> clone() const { return nullptr; }

  double value(const Vec3& p) const { return eval(p, nullptr); }
  Vec3 gradient(const Vec3& p) const {
    Vec3 g;
    eval(p, &g);
    return g;
  }

 protected:
  // Each kind's answer to bounds(b): the value interval and the box Lipschitz bound from one pass
  // over the kind's terms, asking each child's bounds() once (a kind with no box bound of its own
  // gives its global one). Blends over a list of children derive from NaryNode (nary_node.h),
  // which gathers the children's bounds for them. An oracle instruction calls it directly, as
  // Oracle::box_bounds (public there: the program asks the question it stands for).
  NodeBounds box_bounds(const Box& b) const override = 0;
};

using NodePtr = std::unique_ptr<FieldNode>;

}  // namespace softtrace

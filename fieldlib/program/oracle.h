// What an oracle instruction (program.h) asks of the model node behind it: the node evaluates its
// own subtree. Bulge elimination (BT_2 whose ranges follow its children's gradients) stays an
// oracle by design, its bounds derived next to its code (the scale method and BT_k without it
// compile to instructions of their own: their slopes along a segment need their children's,
// docs/math.md §8, "Slopes along a segment"); FieldNode
// (model/node.h) implements this, so the evaluators call it without knowing the model.
#pragma once

#include "math/box.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

// What a node is when it is a polynomial blob (eval/blob_ray.h): a distance function that is
// the distance from q = L x + k to the segment from 0 to `axis` (|q| for an ellipsoid, whose axis
// is 0; a capsule's otherwise, c2 = c3 = 0), or a soft field that is c2 r^2 + c3 r^3 with r = 1 -
// that distance squared where r > 0, and 0 elsewhere.
struct PolynomialBlob {
  Mat3 L;
  Vec3 k;
  Vec3 axis;
  double c2 = 0, c3 = 0;
};

// A node's answer to the box question: f's range and a bound on |∇f| over one box. (The program's
// BoxBounds, eval/eval.h, adds what a ray segment needs; a node answers over boxes only.)
struct NodeBounds {
  Interval value;        // contains f over the box
  double lipschitz = 0;  // >= |∇f| over the box; +inf where no bound exists
};

class Oracle {
 public:
  virtual ~Oracle() = default;
  // f(p), and ∇f(p) into *grad when grad is non-null.
  virtual double eval(const Vec3& p, Vec3* grad) const = 0;
  // A sound enclosure of f over the box and a Lipschitz bound there, together: the node kind's
  // own answer (FieldNode::box_bounds), called with no adapter between, since an oracle blend is
  // asked it for every box of every ray segment (docs/performance.md, "One box question").
  virtual NodeBounds box_bounds(const Box& b) const = 0;
  // Whether the node is a polynomial blob, and which (into *b): what lets the blob ray path read
  // an affinely placed blob, which compiles to one oracle instruction. No by default.
  virtual bool polynomial_blob(PolynomialBlob* b) const { return false; }
};

}  // namespace softtrace

// What an oracle instruction (program.h) asks of the model node behind it: the node evaluates its
// own subtree. The root-defined blends (scale method, BT_k, bulge elimination) stay oracles by
// design, their bounds derived next to their code; FieldNode (model/node.h) implements this, so
// the evaluators call it without knowing the model.
#pragma once

#include "math/box.h"
#include "math/interval.h"
#include "math/vec.h"

namespace softtrace {

class Oracle {
 public:
  virtual ~Oracle() = default;
  // f(p), and ∇f(p) into *grad when grad is non-null.
  virtual double eval(const Vec3& p, Vec3* grad) const = 0;
  // A sound enclosure of f over the box and a Lipschitz bound there, together.
  virtual void bounds(const Box& b, Interval* value, double* lipschitz) const = 0;
};

}  // namespace softtrace

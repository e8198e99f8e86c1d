// The base of the nodes that combine a list of children (soft_blend, the Perlin and Ricci set
// blends, min/max, the scale method, BT_k, the super-ellipsoidal combinations): it owns the
// children and answers the box question by asking each child's bounds() once, so each kind's
// combine() works on bounds already gathered and never walks its children again for the other
// half of the answer (a blend of blends would otherwise ask its grandchildren twice per level).
#pragma once

#include <vector>

#include "model/node.h"

namespace softtrace {

class NaryNode : public FieldNode {
 protected:
  explicit NaryNode(std::vector<NodePtr> children) : c_(std::move(children)) {}

  // The children's bounds over b, child i's interval in I[i] and Lipschitz bound in L[i], handed to
  // combine(); the arrays live on the stack for up to 16 children (math/scratch.h).
  NodeBounds box_bounds(const Box& b) const final;

  // The kind's bounds over b from its children's there (I and L of c_.size() each). b is passed
  // for kinds that ask the children more than their bounds (BT_k's bulge elimination).
  virtual NodeBounds combine(const Box& b, const Interval* I, const double* L) const = 0;

  std::vector<NodePtr> c_;  // the children, in the scene's order
};

}  // namespace softtrace

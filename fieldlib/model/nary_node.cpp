#include "model/nary_node.h"

#include "math/scratch.h"

namespace softtrace {

NodeBounds NaryNode::box_bounds(const Box& b) const {
  const size_t k = c_.size();
  Scratch<Interval> I(k);
  Scratch<double> L(k);
  for (size_t i = 0; i < k; ++i) {
    const NodeBounds child = c_[i]->bounds(b);
    I[i] = child.value;
    L[i] = child.lipschitz;
  }
  return combine(b, I.data(), L.data());
}

}  // namespace softtrace

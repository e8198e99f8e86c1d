#include "model/node.h"

#include "model/program_builder.h"

namespace softtrace {

void FieldNode::bounds(const Box& b, Interval* value, double* lipschitz) const {
  const NodeBounds nb = box_bounds(b);
  *value = nb.value;
  *lipschitz = nb.lipschitz;
}

int FieldNode::compile(ProgramBuilder& b, int reg) const {
  return b.oracle(*this, reg);
}

}  // namespace softtrace

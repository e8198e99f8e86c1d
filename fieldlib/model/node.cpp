#include "model/node.h"

#include "model/program_builder.h"

namespace softtrace {

Interval FieldNode::interval(const Box& b) const {
  const double L = lipschitz(b);
  if (!std::isfinite(L) || !b.bounded()) return Interval::entire();
  const double v = value(b.center()), r = L * 0.5 * b.diagonal();
  return iv::out(v - r, v + r);
}

void FieldNode::bounds(const Box& b, Interval* value, double* L) const {
  *value = interval(b);
  *L = lipschitz(b);
}

int FieldNode::compile(ProgramBuilder& b, int reg) const {
  return b.oracle(*this, reg);
}

}  // namespace softtrace

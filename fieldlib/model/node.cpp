#include "model/node.h"

#include "model/program_builder.h"

namespace softtrace {

int FieldNode::compile(ProgramBuilder& b, int reg) const {
  return b.oracle(*this, reg);
}

}  // namespace softtrace

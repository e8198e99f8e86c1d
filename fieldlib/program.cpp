#include "program.h"

#include <limits>

#include "node.h"
#include "node_util.h"

namespace softtrace {

const char* op_name(Op op) {
  switch (op) {
#define SOFTTRACE_OP_NAME(name) \
  case Op::name:                \
    return #name;
    SOFTTRACE_OPS(SOFTTRACE_OP_NAME)
#undef SOFTTRACE_OP_NAME
  }
  return "?";
}

int ProgramBuilder::compile(const FieldNode& node, int reg) {
  return node.compile(*this, reg);
}

int ProgramBuilder::consts(std::initializer_list<double> c) {
  const int at = static_cast<int>(prog_.consts.size());
  prog_.consts.insert(prog_.consts.end(), c);
  return at;
}

int ProgramBuilder::emit(const Instr& i) {
  prog_.code.push_back(i);
  return i.out;
}

int ProgramBuilder::oracle(const FieldNode& node, int reg) {
  Instr i{Op::Oracle};
  i.out = new_slot();
  i.in = reg;
  i.node = &node;
  return emit(i);
}

int ProgramBuilder::nary(Op op, const std::vector<std::unique_ptr<FieldNode>>& children, int reg) {
  const int g = static_cast<int>(prog_.groups.size());
  prog_.groups.emplace_back();
  Instr head{Op::Group};
  head.a = g;
  emit(head);

  std::vector<Group::Child> kids;
  std::vector<uint8_t> prunable;
  std::vector<Box> supports;
  std::vector<int32_t> ids;
  for (size_t k = 0; k < children.size(); ++k) {
    const FieldNode& c = *children[k];
    const int32_t begin = static_cast<int32_t>(prog_.code.size());
    const int slot = compile(c, reg);
    kids.push_back({begin, static_cast<int32_t>(prog_.code.size()), slot});
    // A term of a sum may be dropped where it is exactly 0: outside the support box of a field
    // that is never negative ({f > 0} lies in region(min, Above), and f >= 0 everywhere).
    bool drop_ok = false;
    if (op == Op::Sum && global_range(c).lo >= 0) {
      const Box support = c.region(std::numeric_limits<double>::min(), Side::Above);
      if (support.bounded() || support.empty()) {
        drop_ok = true;
        supports.push_back(support);
        ids.push_back(static_cast<int32_t>(k));
      }
    }
    prunable.push_back(drop_ok);
  }

  Instr combine{op};
  combine.out = new_slot();
  combine.a = static_cast<int32_t>(prog_.args.size());
  combine.n = static_cast<int32_t>(kids.size());
  for (const auto& k : kids) prog_.args.push_back(k.slot);

  Group& group = prog_.groups[g];
  group.op_index = static_cast<int32_t>(prog_.code.size());
  group.reg = reg;
  group.children = std::move(kids);
  group.prunable = std::move(prunable);
  for (size_t k = 0; k < group.children.size(); ++k)
    if (!group.prunable[k]) group.always.push_back(static_cast<int32_t>(k));
  group.bvh.build(supports, ids);
  return emit(combine);
}

Program ProgramBuilder::finish(int result) {
  prog_.result = result;
  for (const Group& g : prog_.groups) {
    prog_.children += static_cast<int32_t>(g.children.size());
    prog_.has_pruning = prog_.has_pruning || !g.bvh.empty();
  }
  return std::move(prog_);
}

Program compile(const FieldNode& root) {
  ProgramBuilder b;
  const int result = b.compile(root, 0);
  return b.finish(result);
}

}  // namespace softtrace

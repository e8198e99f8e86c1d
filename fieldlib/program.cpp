#include "program.h"

#include <algorithm>
#include <cstdint>
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

int ProgramBuilder::consts(const std::vector<double>& c) {
  const int at = static_cast<int>(prog_.consts.size());
  prog_.consts.insert(prog_.consts.end(), c.begin(), c.end());
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

namespace {
// Spreads the low 21 bits of v to every third bit (for a Morton code).
uint64_t spread3(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// A sum's term is exactly 0 outside its support box if it is a field that is never negative
// ({f > 0} lies in region(min, Above), and f >= 0 everywhere); unbounded for any other term.
Box sum_support(const FieldNode& c) {
  return global_range(c).lo >= 0 ? c.region(std::numeric_limits<double>::min(), Side::Above)
                                 : Box::unbounded();
}
}  // namespace

std::vector<int32_t> ProgramBuilder::compile_order(Op op, const std::vector<Box>& supports) {
  std::vector<int32_t> order(supports.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int32_t>(k);
  // A sum of many soft fields is walked a few nearby children at a time (those a box or a
  // segment meets): compiled in the Morton order of their supports, nearby children's code and
  // constants are near in memory too. Other groups keep the scene's order.
  if (op != Op::Sum || supports.size() < kSpatialOrder) return order;
  Box all;
  for (const Box& b : supports) {
    if (!b.bounded() || b.empty()) return order;
    all.extend(b.center());
  }
  std::vector<uint64_t> key(supports.size());
  const Vec3 e = all.extent();
  for (size_t k = 0; k < supports.size(); ++k) {
    const Vec3 c = supports[k].center() - all.lo;
    uint64_t code = 0;
    for (int i = 0; i < 3; ++i) {
      const double u = e[i] > 0 ? c[i] / e[i] : 0;
      code |= spread3(static_cast<uint64_t>(std::clamp(u, 0.0, 1.0) * 0x1fffff)) << i;
    }
    key[k] = code;
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return key[a] < key[b]; });
  return order;
}

int ProgramBuilder::nary(Op op, const std::vector<std::unique_ptr<FieldNode>>& children, int reg,
                         int consts_at) {
  const int g = static_cast<int>(prog_.groups.size());
  prog_.groups.emplace_back();
  Instr head{Op::Group};
  head.a = g;
  emit(head);

  std::vector<Group::Child> kids;
  std::vector<uint8_t> prunable;
  std::vector<Box> supports;  // of the prunable children, for the BVH
  std::vector<int32_t> ids;
  // A term of a sum may be dropped where it is exactly 0: outside a bounded support.
  std::vector<Box> child_supports(children.size(), Box::unbounded());
  if (op == Op::Sum)
    for (size_t k = 0; k < children.size(); ++k) child_supports[k] = sum_support(*children[k]);
  const std::vector<int32_t> order = compile_order(op, child_supports);
  for (size_t k = 0; k < children.size(); ++k) {
    const int32_t begin = static_cast<int32_t>(prog_.code.size());
    const int slot = compile(*children[order[k]], reg);
    kids.push_back({begin, static_cast<int32_t>(prog_.code.size()), slot});
    const Box& support = child_supports[order[k]];
    const bool drop_ok = support.bounded() || support.empty();
    if (drop_ok) {
      supports.push_back(support);
      ids.push_back(static_cast<int32_t>(k));
    }
    prunable.push_back(drop_ok);
  }

  Instr combine{op};
  combine.out = new_slot();
  combine.in = consts_at;
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

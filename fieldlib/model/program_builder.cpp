#include "model/program_builder.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "model/node_util.h"

namespace softtrace {

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

int ProgramBuilder::single(Op op, int in, const std::vector<double>& c, int32_t n) {
  Instr i{op};
  i.in = in;
  i.out = new_slot();
  i.a = consts(c);
  i.n = n;
  return emit(i);
}

int ProgramBuilder::oracle(const FieldNode& node, int reg) {
  Instr i{Op::Oracle};
  i.out = new_slot();
  i.in = reg;
  i.node = &node;
  return emit(i);
}

namespace {
// A sum's term is exactly 0 outside its support box if it is a field that is never negative
// ({f > 0} lies in region(min, Above), and f >= 0 everywhere) or never positive ({f < 0} lies in
// region(-min, Below): a soft object of negative strength); unbounded for any other term.
Box sum_support(const FieldNode& c) {
  const double tiny = std::numeric_limits<double>::min();
  const Interval range = global_range(c);
  if (range.lo >= 0) return c.region(tiny, Side::Above);
  if (range.hi <= 0) return c.region(-tiny, Side::Below);
  return Box::unbounded();
}
}  // namespace

std::vector<int32_t> ProgramBuilder::compile_order(Op op, const std::vector<Box>& supports,
                                                   BoxBvh* tree) {
  std::vector<int32_t> order(supports.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int32_t>(k);
  // A sum of many soft fields is walked a few nearby children at a time (those a box or a
  // segment meets): compiled in the order of the leaves of a hierarchy over their supports,
  // nearby children's code and constants are near in memory, and every query of that hierarchy
  // finds its children in ascending order, with no sort. Other groups keep the scene's order.
  if (op != Op::Sum || supports.size() < kSpatialOrder) return order;
  for (const Box& b : supports)
    if (!b.bounded() || b.empty()) return order;
  tree->build(supports, order);
  order = tree->tree_order();
  std::vector<int32_t> position(order.size());
  for (size_t k = 0; k < order.size(); ++k) position[order[k]] = static_cast<int32_t>(k);
  tree->relabel(position);
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
  BoxBvh spatial;  // built by compile_order where it orders the children by it
  const std::vector<int32_t> order = compile_order(op, child_supports, &spatial);
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
    if (op == Op::Sum && !terms_.empty()) {
      const auto it = std::find(terms_.begin(), terms_.end(), children[order[k]].get());
      if (it != terms_.end()) {
        prog_.groups[g].terms.resize(children.size(), -1);
        prog_.groups[g].terms[k] = static_cast<int32_t>(it - terms_.begin());
        ++prog_.terms;
      }
    }
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
  if (spatial.empty()) {
    group.bvh.build(supports, ids);
  } else {
    group.bvh = std::move(spatial);  // over every child, by compiled position
  }
  return emit(combine);
}

Program ProgramBuilder::finish(int result) {
  prog_.result = result;
  for (const Group& g : prog_.groups) {
    prog_.children += static_cast<int32_t>(g.children.size());
    prog_.has_pruning = prog_.has_pruning || !g.bvh.empty();
  }
  share_storage(prog_);
  return std::move(prog_);
}

Program compile(const FieldNode& root, const std::vector<const FieldNode*>& terms) {
  ProgramBuilder b(terms);
  const int result = b.compile(root, 0);
  Program p = b.finish(result);
  if (p.terms != static_cast<int32_t>(terms.size()))
    throw std::logic_error("compile: " + std::to_string(terms.size() - size_t(p.terms)) +
                           " of the terms asked for are no sum's children");
  return p;
}

}  // namespace softtrace

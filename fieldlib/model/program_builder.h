// Compiling the model to a flat program (program/program.h): each node emits its own instructions
// through ProgramBuilder (FieldNode::compile), or one oracle instruction that calls it back.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <vector>

#include "model/node.h"
#include "program/program.h"

namespace softtrace {

// Builds a program from a model node; FieldNode::compile calls back into it.
class ProgramBuilder {
 public:
  // `terms`: nodes that are children of sums, whose values the evaluators can report beside f
  // (Program::terms, Group::terms), term i being terms[i].
  explicit ProgramBuilder(std::vector<const FieldNode*> terms = {}) : terms_(std::move(terms)) {}

  // Emits the subtree of `node` reading point register `reg`; returns its result slot.
  int compile(const FieldNode& node, int reg);

  int new_slot() { return prog_.slots++; }
  int new_reg() { return prog_.regs++; }
  int consts(std::initializer_list<double> c);
  int consts(const std::vector<double>& c);
  template <size_t N>
  int consts(const std::array<double, N>& c) {
    const int at = static_cast<int>(prog_.consts.size());
    prog_.consts.insert(prog_.consts.end(), c.begin(), c.end());
    return at;
  }
  int emit(const Instr& i);
  // One instruction of `op` over `in` (a point register for a distance, a value slot for an op
  // over one slot) with the constants `c` in its struct's layout (program/ops/) and `n` where that
  // struct reads it; writes a new slot, which it returns.
  int single(Op op, int in, const std::vector<double>& c, int32_t n = 0);

  // An oracle instruction: `node` evaluates its own subtree at register `reg`.
  int oracle(const FieldNode& node, int reg);
  // Emits `children` as a group combined by `op` (Sum, Min, Max, SuperUnion, SuperIntersect,
  // Perlin, Ricci, Scale), whose `in` is `consts_at`; for Sum, children whose value is exactly 0
  // outside their support are made prunable.
  int nary(Op op, const std::vector<std::unique_ptr<FieldNode>>& children, int reg,
           int consts_at = 0);

  Program finish(int result);

 private:
  // The order `nary` compiles the children in, given their supports (unbounded where a child is
  // never dropped): a large sum's in the order of the leaves of a BVH over their supports (its
  // value changes only by the rounding of the sum's order), which is then left in *tree with the
  // children's compiled positions as ids; the scene's order, and *tree empty, otherwise.
  static std::vector<int32_t> compile_order(Op op, const std::vector<Box>& supports, BoxBvh* tree);
  // The number of children from which a sum is compiled in spatial order.
  static constexpr size_t kSpatialOrder = 32;

  Program prog_;
  std::vector<const FieldNode*> terms_;
};

// `root` compiled; each of `terms` must be a child of a soft_blend (a sum) in it, and becomes the
// program's term of its index (std::logic_error otherwise).
Program compile(const FieldNode& root, const std::vector<const FieldNode*>& terms = {});

}  // namespace softtrace

// Shared storage for a compiled program's values. The builder hands out a new slot or register for
// every value (the code is in SSA form), but most live only from one instruction to the next: a
// blob's local point and its distance. A linear scan over the straight-line code (as fidget
// allocates registers) renumbers them so that values whose lifetimes do not overlap share storage.
// The workspace then grows with the most values alive at once, not with the program's length: a
// sum of 10,000 blobs keeps its 10,000 terms' slots, side by side, and one point and one distance
// for all of them, so a box pass over nearby blobs touches a few cache lines instead of scattered
// ones.
//
// Pruning stays valid: a view drops whole child ranges, and a value defined inside a child is used
// only inside it or, its result, by the combining instruction, whose argument list drops it too.
#include <algorithm>
#include <limits>
#include <queue>
#include <vector>

#include "program/ops/ops.h"
#include "program/program.h"

namespace softtrace {

namespace {

// Calls use(space, id&) for every value instruction k reads, then def(space, id&) for the one it
// writes (if any): its op's operands (ops.h).
template <class Use, class Def>
void operands(Program& p, int k, const Use& use, const Def& def) {
  Instr& in = p.code[k];
  switch (in.op) {
#define SOFTTRACE_OP_OPERANDS(name)      \
  case Op::name:                         \
    name##Op::operands(in, p, use, def); \
    return;
    SOFTTRACE_OPS(SOFTTRACE_OP_OPERANDS)
#undef SOFTTRACE_OP_OPERANDS
  }
}

// The lowest free number of one space, or a new one.
class Pool {
 public:
  int take() {
    if (free_.empty()) return size_++;
    const int s = free_.top();
    free_.pop();
    return s;
  }
  void give(int s) { free_.push(s); }
  void reserve(int s) { size_ = std::max(size_, s + 1); }
  int size() const { return size_; }

 private:
  std::priority_queue<int, std::vector<int>, std::greater<int>> free_;
  int size_ = 0;
};

}  // namespace

void share_storage(Program& p) {
  const int n = static_cast<int>(p.code.size());
  constexpr int kNever = -1, kForever = std::numeric_limits<int>::max(), kGone = -2;
  // The last instruction that reads each value (SSA: each id is written once).
  std::vector<int> last[2] = {std::vector<int>(p.slots, kNever), std::vector<int>(p.regs, kNever)};
  for (int k = 0; k < n; ++k)
    operands(
        p, k, [&](Space s, int32_t& id) { last[s][id] = std::max(last[s][id], k); },
        [](Space, int32_t&) {});
  last[kSlot][p.result] = kForever;
  last[kReg][0] = kForever;  // the evaluation point

  std::vector<int32_t> to[2] = {std::vector<int32_t>(p.slots, -1),
                                std::vector<int32_t>(p.regs, -1)};
  Pool pool[2];
  to[kReg][0] = 0;
  pool[kReg].reserve(0);
  for (int k = 0; k < n; ++k) {
    // The value written first, so that it never shares storage with what the instruction reads
    // (the evaluators read their operands' bounds after writing some of the result's).
    operands(
        p, k, [](Space, int32_t&) {},
        [&](Space s, int32_t& id) {
          to[s][id] = pool[s].take();
          if (last[s][id] == kNever) last[s][id] = k;  // never read: free at once
        });
    const auto release = [&](Space s, int32_t& id) {
      if (last[s][id] != k) return;
      pool[s].give(to[s][id]);
      last[s][id] = kGone;  // an id read twice by one instruction is freed once
    };
    operands(p, k, release, release);
  }

  const auto rename = [&](Space s, int32_t& id) { id = to[s][id]; };
  for (int k = 0; k < n; ++k)
    if (p.code[k].op != Op::Group) operands(p, k, rename, rename);  // a group's register: below
  for (Group& g : p.groups) {
    rename(kReg, g.reg);
    for (Group::Child& c : g.children) rename(kSlot, c.slot);
  }
  rename(kSlot, p.result);
  p.slots = pool[kSlot].size();
  p.regs = pool[kReg].size();
}

}  // namespace softtrace

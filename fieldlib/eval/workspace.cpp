#include <algorithm>

#include "eval/eval.h"

namespace softtrace {

namespace {
template <class V>
void grow(V& v, size_t n) {
  if (v.size() < n) v.resize(n);
}
}  // namespace

void Workspace::grow_to(const WorkspaceNeed& n) {
  const size_t slots_n = std::max(n.slots, held_.slots), regs_n = std::max(n.regs, held_.regs);
  const size_t children_n = std::max(n.children, held_.children);
  grow(ends, GaugeEnds::kTable);
  grow(slots, slots_n * kBatch);
  grow(regs, regs_n * 3 * kBatch);
  grow(points, regs_n);
  grow(duals, slots_n);
  grow(frames, regs_n);
  grow(ivals, slots_n);
  grow(lips, slots_n);
  grow(boxes, regs_n);
  grow(segs, regs_n * 2);
  grow(seg_pads, regs_n);
  grow(slopes, slots_n);
  grow(quiet, slots_n);
  grow(kept, children_n);
  grow(marks, children_n);
  if (view.code.capacity() < n.code) view.code.reserve(n.code);
  if (view.args.capacity() < n.args) view.args.reserve(n.args);
  held_.slots = slots_n;
  held_.regs = regs_n;
  held_.children = children_n;
  held_.code = std::max(n.code, held_.code);
  held_.args = std::max(n.args, held_.args);
}

}  // namespace softtrace

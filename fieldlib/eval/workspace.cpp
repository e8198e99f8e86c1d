#include <algorithm>

#include "eval/eval.h"

namespace softtrace {

namespace {
template <class T>
void grow(std::vector<T>& v, size_t n) {
  if (v.size() < n) v.resize(n);
}
}  // namespace

void Workspace::grow_to(const Program& p) {
  const size_t slots_n = std::max<int32_t>(p.slots, 1), regs_n = p.regs;
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
  grow(kept, size_t(p.children) + 1);
  grow(marks, size_t(p.children) + 1);
  if (view.code.capacity() < p.code.size()) view.code.reserve(p.code.size());
  if (view.args.capacity() < p.args.size()) view.args.reserve(p.args.size());
}

}  // namespace softtrace

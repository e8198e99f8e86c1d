#include "model/nary_node.h"

#include <memory>
#include <new>

#include "math/scratch.h"

namespace softtrace {

namespace {

// k intervals, on the stack up to 16 as in Scratch, but not initialised: each slot is constructed
// as it is written, and every one is written before combine() reads it. (Scratch<Interval> zeroes
// all 16 first, which was a third of this function's instructions per call under callgrind on
// the scale-union and BT scenes, where an oracle blend asks it for every box.)
class IntervalSlots {
 public:
  explicit IntervalSlots(size_t k) : heap_(k > kStack ? new Interval[k] : nullptr) {
    p_ = heap_ ? heap_.get() : reinterpret_cast<Interval*>(stack_);
  }
  IntervalSlots(const IntervalSlots&) = delete;
  IntervalSlots& operator=(const IntervalSlots&) = delete;

  void set(size_t i, Interval v) { new (p_ + i) Interval(v); }  // trivially destructible
  const Interval* data() const { return p_; }

 private:
  static constexpr size_t kStack = 16;
  alignas(Interval) unsigned char stack_[kStack * sizeof(Interval)];
  std::unique_ptr<Interval[]> heap_;
  Interval* p_;
};

}  // namespace

NodeBounds NaryNode::box_bounds(const Box& b) const {
  const size_t k = c_.size();
  IntervalSlots I(k);
  Scratch<double> L(k);
  for (size_t i = 0; i < k; ++i) {
    const NodeBounds child = c_[i]->bounds(b);
    I.set(i, child.value);
    L[i] = child.lipschitz;
  }
  return combine(b, I.data(), L.data());
}

}  // namespace softtrace

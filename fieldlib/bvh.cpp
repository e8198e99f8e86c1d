#include "bvh.h"

#include <algorithm>
#include <numeric>

namespace softtrace {

namespace {
constexpr int32_t kLeafSize = 4;
constexpr int kMaxDepth = 64;

bool overlaps(const Box& a, const Box& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
         a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}
}  // namespace

void BoxBvh::build(const std::vector<Box>& boxes, const std::vector<int32_t>& ids) {
  nodes_.clear();
  items_.clear();
  item_boxes_.clear();
  for (size_t i = 0; i < boxes.size(); ++i)
    if (!boxes[i].empty()) {
      items_.push_back(ids[i]);
      item_boxes_.push_back(boxes[i]);
    }
  if (items_.empty()) return;
  std::vector<Box> scratch;
  build(0, static_cast<int32_t>(items_.size()), scratch);
}

int32_t BoxBvh::build(int32_t first, int32_t count, std::vector<Box>& scratch) {
  const int32_t index = static_cast<int32_t>(nodes_.size());
  nodes_.push_back({});
  Box box, centres;
  for (int32_t i = first; i < first + count; ++i) {
    box = box.united(item_boxes_[i]);
    centres.extend(item_boxes_[i].center());
  }
  nodes_[index].box = box;
  // Depth is bounded by the median split (log2 n), far below kMaxDepth for any allowed scene.
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const Vec3 e = centres.extent();
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  const int32_t half = count / 2;
  // Sort the range by centre along the axis, carrying ids and boxes together.
  std::vector<int32_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::nth_element(order.begin(), order.begin() + half, order.end(), [&](int32_t a, int32_t b) {
    const double ca = item_boxes_[first + a].center()[axis],
                 cb = item_boxes_[first + b].center()[axis];
    return ca < cb || (ca == cb && items_[first + a] < items_[first + b]);
  });
  std::vector<int32_t> ids(count);
  scratch.resize(count);
  for (int32_t i = 0; i < count; ++i) {
    ids[i] = items_[first + order[i]];
    scratch[i] = item_boxes_[first + order[i]];
  }
  std::copy(ids.begin(), ids.end(), items_.begin() + first);
  std::copy(scratch.begin(), scratch.begin() + count, item_boxes_.begin() + first);
  const int32_t left = build(first, half, scratch);
  const int32_t right = build(first + half, count - half, scratch);
  nodes_[index].count = 0;
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

namespace {
// The slab test of the segment a + s (b - a), s in [0, 1], against boxes grown by pad, with the
// reciprocals taken once per query. The slack on s covers the products' rounding, far below what
// pad adds. An axis the segment does not move along compares a's coordinate instead; a NaN
// (0 times an infinite reciprocal) constrains nothing, as std::min/max keep the other operand.
class SegmentTest {
 public:
  SegmentTest(const Vec3& a, const Vec3& b, double pad) : a_(a), pad_(pad) {
    for (int i = 0; i < 3; ++i) {
      const double e = b[i] - a[i];
      flat_[i] = e == 0;
      inv_[i] = flat_[i] ? 0 : 1 / e;
    }
  }
  bool meets(const Box& box) const {
    double s0 = 0, s1 = 1;
    for (int i = 0; i < 3; ++i) {
      const double lo = box.lo[i] - pad_, hi = box.hi[i] + pad_;
      if (flat_[i]) {
        if (a_[i] < lo || a_[i] > hi) return false;
        continue;
      }
      const double u = (lo - a_[i]) * inv_[i], v = (hi - a_[i]) * inv_[i];
      s0 = std::max(s0, std::min(u, v));
      s1 = std::min(s1, std::max(u, v));
    }
    return s0 <= s1 + 1e-12;
  }

 private:
  Vec3 a_;
  double pad_, inv_[3];
  bool flat_[3];
};
}  // namespace

template <class NodeTest, class ItemTest>
int BoxBvh::walk(const NodeTest& node_test, const ItemTest& item_test, int32_t* out,
                 int count) const {
  if (nodes_.empty()) return count;
  int32_t stack[kMaxDepth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!node_test(n.box)) continue;
    if (n.count > 0) {
      for (int32_t i = n.first; i < n.first + n.count; ++i)
        if (item_test(item_boxes_[i])) out[count++] = items_[i];
      continue;
    }
    stack[top++] = n.right;
    stack[top++] = n.left;
  }
  return count;
}

template <class Accept>
int BoxBvh::collect(const Box& q, const Accept& accept, int32_t* out, int count) const {
  const auto in_q = [&](const Box& box) { return overlaps(box, q); };
  const int end = walk(
      in_q, [&](const Box& box) { return in_q(box) && accept(box); }, out, count);
  // Children are combined in their scene order, so results do not depend on the tree's shape.
  std::sort(out + count, out + end);
  return end;
}

int BoxBvh::query(const Box& q, int32_t* out, int count) const {
  return collect(
      q, [](const Box&) { return true; }, out, count);
}

int BoxBvh::query(const Box& q, const Vec3& a, const Vec3& b, double pad, int32_t* out,
                  int count) const {
  const SegmentTest segment(a, b, pad);
  return collect(
      q, [&](const Box& box) { return segment.meets(box); }, out, count);
}

int BoxBvh::segment_items(const Vec3& a, const Vec3& b, double pad, int32_t* out) const {
  const SegmentTest segment(a, b, pad);
  const auto meets = [&](const Box& box) { return segment.meets(box); };
  return walk(meets, meets, out, 0);
}

}  // namespace softtrace

// A bounding-volume hierarchy over axis-aligned boxes, for pruning: which of many children's
// support boxes overlap a query box, in O(log n + k). Built once per blend at compile time
// (median split on the longest axis of the centroids, a few boxes per leaf); queried from many
// threads at once (const, no allocation: the caller owns the output buffer).
#pragma once

#include <cstdint>
#include <vector>

#include "box.h"

namespace softtrace {

class BoxBvh {
 public:
  // `boxes[i]` is item `ids[i]`'s box; empty boxes are never reported.
  void build(const std::vector<Box>& boxes, const std::vector<int32_t>& ids);
  bool empty() const { return nodes_.empty(); }

  // Appends to out[count..] the ids of the items whose boxes overlap `q` (closed boxes), in
  // increasing id order among themselves; returns the new count. `out` must have room for every
  // item.
  int query(const Box& q, int32_t* out, int count) const;
  // The same for the items whose boxes, grown by `pad`, the segment [a, b] meets (and that
  // overlap `q`, a box holding the segment): the children a stretch of a ray passes through, as
  // POV-Ray's blob keeps the list of support entries and exits along its ray.
  int query(const Box& q, const Vec3& a, const Vec3& b, double pad, int32_t* out, int count) const;
  // The same items in the order of the tree (not sorted): every node is tested against the
  // segment itself, which pays on long segments, whose bounding box holds far more nodes than
  // the segment meets (blob_ray.h's stretches of a ray). Returns how many were written to out.
  int segment_items(const Vec3& a, const Vec3& b, double pad, int32_t* out) const;

 private:
  struct Node {
    Box box;
    int32_t first, count;  // leaf: items_[first, first+count); inner: count = 0, children
    int32_t left, right;
  };
  int32_t build(int32_t first, int32_t count, std::vector<Box>& centre_boxes);
  // The items whose boxes pass item_test and whose nodes' boxes all pass node_test, appended to
  // out[count..] in the tree's order (left first); returns the new count.
  template <class NodeTest, class ItemTest>
  int walk(const NodeTest& node_test, const ItemTest& item_test, int32_t* out, int count) const;
  // The items whose boxes overlap q and pass `accept`, appended in id order.
  template <class Accept>
  int collect(const Box& q, const Accept& accept, int32_t* out, int count) const;

  std::vector<Node> nodes_;
  std::vector<int32_t> items_;  // ids
  std::vector<Box> item_boxes_;
};

}  // namespace softtrace

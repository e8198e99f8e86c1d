// A bounding-volume hierarchy over axis-aligned boxes, for pruning: which of many children's
// support boxes overlap a query box, or a stretch of a ray passes through, in O(log n + k). Built
// once per blend at compile time; queried from many threads at once (const, no allocation: the
// caller owns the output buffer).
//
// Four children per node, their boxes stored axis by axis (Embree's BVH4 layout) and tested two at
// a time in SSE2 registers, in double precision so the tests are exactly the scalar ones. The tree
// is a binned surface-area-heuristic binary tree, up to kLeafItems items per leaf, collapsed into
// nodes of four. A leaf's items are tested block after block, four at a time: its blocks lie side
// by side, so their loads do not wait on one another as a walk down more levels of nodes would.
#pragma once

#include <cstdint>
#include <vector>

#include "math/box.h"

namespace softtrace {

class BoxBvh {
 public:
  // `boxes[i]` is item `ids[i]`'s box; empty boxes are never reported.
  void build(const std::vector<Box>& boxes, const std::vector<int32_t>& ids);
  bool empty() const { return blocks_.empty(); }  // every item lies in a block
  // The items' ids in the order every query reports them (the walk's, the same for any query).
  std::vector<int32_t> tree_order() const;
  // Renames item `id` to `to[id]`. Where that makes the tree's order ascending, the queries below
  // skip their sort.
  void relabel(const std::vector<int32_t>& to);

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
  // The items whose boxes are not wholly outside one of the four half-spaces dot(x - apex,
  // normals[i]) >= -pad (a pyramid: the frustum of a block of camera rays), in the order of the
  // tree, as segment_items reports them. Returns how many were written to out.
  int cone_items(const Vec3& apex, const Vec3 (&normals)[4], double pad, int32_t* out) const;
  // The same with a pad per half-space, dot(x - apex, normals[i]) >= -pads[i]: planes that need
  // not pass through one point (a prism's sides, each pads[i] from `apex`).
  int cone_items(const Vec3& apex, const Vec3 (&normals)[4], const double (&pads)[4],
                 int32_t* out) const;
  // The same with a node's four slots tested two at a time (SSE2) or all four at once (AVX2,
  // only where cpu_has_avx2()): the same items in the same order. The overloads above take the
  // four where the CPU has them.
  enum class ConeLanes { kPairs, kFour };
  int cone_items(const Vec3& apex, const Vec3 (&normals)[4], const double (&pads)[4], int32_t* out,
                 ConeLanes lanes) const;

  static constexpr int kWidth = 4;
  static constexpr int kLeafItems = 16;
  static constexpr int kBlockBits = 2;  // a leaf's block count - 1 fits in these
  static_assert(kLeafItems <= kWidth << kBlockBits);
  // A node: its children's boxes, axis by axis (lo[axis][child]); ref >= 0 is a child node's
  // index, ref < 0 a leaf: blocks_[~ref >> kBlockBits] and the (~ref & 3) blocks after it. A
  // block is laid out as a node, with ref the items' ids. Slots at and after `size` are unused.
  struct Node {
    double lo[3][kWidth], hi[3][kWidth];
    int32_t ref[kWidth];
    int32_t size;
  };

 private:
  // kScattered: for queries in no order (boxes anywhere); the rays' stretches, one after another
  // along a ray and from ray to ray, pass the same slots often enough for branches to pay.
  template <bool kScattered, class Test>
  int walk(const Test& test, int32_t* out, int count) const;
  // A leaf's items (a slot's ref < 0) that pass `test`, appended to out[count..].
  template <class Test>
  int leaf_items(int32_t ref, const Test& test, int32_t* out, int count) const;

  void note_order();

  // The root is nodes_[0]. At most kWidth items make no node: the tree is then blocks_[0] alone,
  // tested with no node above it (a blend of two soft objects paid three tests for two items).
  std::vector<Node> nodes_;
  std::vector<Node> blocks_;  // the leaves' items, four to a block
  bool ascending_ = false;    // ids ascend in the tree's order
};

}  // namespace softtrace

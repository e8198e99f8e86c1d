#include "math/bvh.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>

#ifdef __SSE2__
#include <emmintrin.h>
#endif
#include <immintrin.h>

#include "math/cpu_avx2.h"

namespace softtrace {

namespace {
// Past this depth the binary tree splits at the median: the surface-area heuristic can cut one
// item at a time off a badly graded set, and the walk's stack is sized for depth 32 + log2 n.
constexpr int kSahDepth = 32;
constexpr int kBins = 16;
static_assert(kBins <= 32, "sah_split keeps the occupied bins as bits of a uint32_t");
constexpr int kStack = 256;  // at most (kWidth - 1) per level of the collapsed tree, plus one

// The binary tree the build makes first, one item per leaf; a node's subtree holds items
// [first, first + count) of the builder's (reordered) arrays. The collapsed tree's leaves are the
// subtrees of at most kLeafItems items, their items in the binary tree's order: nearby items stay
// next to each other in it, and so do the children a sum compiles in that order.
struct Binary {
  Box box;
  int32_t left = -1, right = -1;
  int32_t first = 0, count = 0;
  bool leaf() const { return count <= BoxBvh::kLeafItems; }
};

// b.extend(item.lo) and then b.extend(item.hi), two coordinates at a time: GCC made twelve scalar
// minima and maxima of it, and it was most of the binning's work. SSE2's min(p, x) answers
// (p < x) ? p : x, as std::min(x, p) does, and max(p, x) (p > x) ? p : x, as std::max(x, p)
// does (the second operand where either is NaN or both are zeros of either sign), so the box's
// bits are extend's.
inline void extend_by(Box& b, const Box& item) {
#ifdef __SSE2__
  const __m128d lo_xy = _mm_loadu_pd(&item.lo.x), hi_xy = _mm_loadu_pd(&item.hi.x);
  const __m128d lo_z = _mm_load_sd(&item.lo.z), hi_z = _mm_load_sd(&item.hi.z);
  _mm_storeu_pd(&b.lo.x, _mm_min_pd(hi_xy, _mm_min_pd(lo_xy, _mm_loadu_pd(&b.lo.x))));
  _mm_storeu_pd(&b.hi.x, _mm_max_pd(hi_xy, _mm_max_pd(lo_xy, _mm_loadu_pd(&b.hi.x))));
  _mm_store_sd(&b.lo.z, _mm_min_sd(hi_z, _mm_min_sd(lo_z, _mm_load_sd(&b.lo.z))));
  _mm_store_sd(&b.hi.z, _mm_max_sd(hi_z, _mm_max_sd(lo_z, _mm_load_sd(&b.hi.z))));
#else
  b.extend(item.lo);
  b.extend(item.hi);
#endif
}

// extend_by for an item whose lo lies below its hi on every axis (no NaN, no flat axis): the
// minimum of the los and the maximum of the his alone, half the instructions. With lo < hi,
// min(hi, min(lo, p)) is min(lo, p) (hi wins only below it, and it is at most lo) and
// max(hi, max(lo, p)) is max(hi, p), operands and all, so the bits are extend_by's; a flat axis
// would not do (lo = +0, hi = -0 makes the first max +0 and this one -0). Such items' union,
// a bin's or a node's box, is such a box again.
inline void extend_by_ordered(Box& b, const Box& item) {
#ifdef __SSE2__
  _mm_storeu_pd(&b.lo.x, _mm_min_pd(_mm_loadu_pd(&item.lo.x), _mm_loadu_pd(&b.lo.x)));
  _mm_storeu_pd(&b.hi.x, _mm_max_pd(_mm_loadu_pd(&item.hi.x), _mm_loadu_pd(&b.hi.x)));
  _mm_store_sd(&b.lo.z, _mm_min_sd(_mm_load_sd(&item.lo.z), _mm_load_sd(&b.lo.z)));
  _mm_store_sd(&b.hi.z, _mm_max_sd(_mm_load_sd(&item.hi.z), _mm_load_sd(&b.hi.z)));
#else
  extend_by(b, item);
#endif
}

// Every box's lo below its hi on every axis: where it holds, extend_by_ordered gives the bits of
// extend_by, and a bin that took an item is never empty.
bool all_ordered(const std::vector<Box>& boxes) {
  for (const Box& b : boxes)
    if (!(b.lo.x < b.hi.x && b.lo.y < b.hi.y && b.lo.z < b.hi.z)) return false;
  return true;
}

double half_area(const Box& b) {
  const Vec3 e = b.extent();
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

class BinaryBuilder {
 public:
  BinaryBuilder(std::vector<Box> boxes, std::vector<int32_t> ids) {
    Items& at_root = items_[0];
    at_root.boxes = std::move(boxes);
    at_root.ids = std::move(ids);
    const size_t n = at_root.ids.size();
    for (int axis = 0; axis < 3; ++axis) {
      at_root.centre[axis].reserve(n);
      keys_[axis].resize(n);
      items_[1].centre[axis].resize(n);
    }
    items_[1].boxes.resize(n);
    items_[1].ids.resize(n);
    nodes.reserve(2 * n - 1);  // a binary tree of n leaves
    for (const Box& b : at_root.boxes) {
      const Vec3 c = b.center();
      at_root.centre[0].push_back(c.x);
      at_root.centre[1].push_back(c.y);
      at_root.centre[2].push_back(c.z);
    }
  }

  std::vector<Binary> nodes;
  // The items in the order of the tree's leaves, once build() has returned.
  const std::vector<Box>& boxes() const { return items_[0].boxes; }
  const std::vector<int32_t>& ids() const { return items_[0].ids; }

  // kOrdered: every item's lo lies below its hi (all_ordered), and the boxes are united by
  // extend_by_ordered.
  template <bool kOrdered>
  int32_t build(int32_t first, int32_t count, int depth) {
    const int32_t index = static_cast<int32_t>(nodes.size());
    nodes.emplace_back();
    const Items& in = items_[depth & 1];
    Box box, centres;
    for (int32_t i = first; i < first + count; ++i) {
      extend<kOrdered>(box, in.boxes[i]);  // united(): no item is empty
      centres.extend({in.centre[0][i], in.centre[1][i], in.centre[2][i]});
    }
    nodes[index].box = box;
    nodes[index].first = first;
    nodes[index].count = count;
    if (count == 1) {
      if (depth & 1) {  // a leaf's item ends in the first arrays
        items_[0].ids[first] = in.ids[first];
        items_[0].boxes[first] = in.boxes[first];
      }
      return index;
    }
    Items& out = items_[~depth & 1];
    int32_t half = depth < kSahDepth ? sah_split<kOrdered>(in, first, count, centres, out) : 0;
    if (half <= 0) half = median_split(in, first, count, centres, out);
    const int32_t left = build<kOrdered>(first, half, depth + 1);
    const int32_t right = build<kOrdered>(first + half, count - half, depth + 1);
    nodes[index].left = left;
    nodes[index].right = right;
    return index;
  }

 private:
  // The items' ids, boxes and centres (axis by axis: the axis is a loop variable, and reading a
  // Vec3's coordinate by it took a branch per read). A node at depth d finds its items in
  // items_[d & 1] and hands them to its children split in the other: each item is written once a
  // level, where a split in place moved the right side's items through a scratch and back (a
  // copy per array and node, five calls of memcpy, mostly for a few items).
  struct Items {
    std::vector<int32_t> ids;
    std::vector<Box> boxes;
    std::vector<double> centre[3];
  };

  template <bool kOrdered>
  static void extend(Box& b, const Box& item) {
    if (kOrdered) {
      extend_by_ordered(b, item);
    } else {
      extend_by(b, item);
    }
  }

  // x = (centre - lo) / w, the centre's place in the range [lo, lo + w] of the node's centres.
  // An unbounded item's centre may be infinite or NaN: the last bin or the first.
  static int bin_of(double x) {
    return x >= 1 ? kBins - 1 : x > 0 ? static_cast<int>(x * kBins) : 0;
  }

  // The binned surface-area heuristic: the split between bins along an axis that least
  // increases A_left n_left + A_right n_right. Writes the range's items to `out`, the first
  // `half` those that go left; returns half, or 0 where no split is finite (unbounded boxes,
  // equal centres), with nothing written. Each item's bin along each axis is kept from the
  // binning for the partition.
  template <bool kOrdered>
  int32_t sah_split(const Items& in, int32_t first, int32_t count, const Box& centres, Items& out) {
    double best = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    int32_t best_left = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = centres.lo[axis], w = centres.hi[axis] - lo;
      if (!(w > 0) || !std::isfinite(w)) continue;
      Box bins[kBins];
      int32_t n[kBins] = {};
      uint32_t occupied = 0;  // bit k: bin k has items
      uint8_t* key = keys_[axis].data();
      const double* centre = in.centre[axis].data() + first;
      const Box* box = in.boxes.data() + first;
      for (int32_t i = 0; i < count; ++i) {
        const int k = bin_of((centre[i] - lo) / w);
        key[i] = static_cast<uint8_t>(k);
        extend<kOrdered>(bins[k], box[i]);  // united(), whose empty() test no item needs
        ++n[k];
        occupied |= 1u << k;
      }
      // Only the splits between the first and the last occupied bins leave items on both sides,
      // and an empty bin's split costs what the split before it did (the same boxes either
      // side): the sweeps visit the occupied bins alone, listed in order from the mask (most of
      // a small range's bins are empty, and stepping over them was most of its work).
      int bin[kBins], m = 0;
      for (uint32_t rest = occupied; rest != 0; rest &= rest - 1) bin[m++] = __builtin_ctz(rest);
      double right_area[kBins];  // of the occupied bins bin[j..m)
      Box acc;
      for (int j = m - 1; j > 0; --j) {
        if (kOrdered || !bins[bin[j]].empty()) extend<kOrdered>(acc, bins[bin[j]]);  // united()
        right_area[j] = half_area(acc);
      }
      acc = Box();
      int32_t left = 0;
      for (int j = 0; j + 1 < m; ++j) {
        if (kOrdered || !bins[bin[j]].empty()) extend<kOrdered>(acc, bins[bin[j]]);
        left += n[bin[j]];
        const double cost = half_area(acc) * left + right_area[j + 1] * (count - left);
        if (cost < best) {
          best = cost;
          best_axis = axis;
          best_bin = bin[j];
          best_left = left;
        }
      }
      // Two items: on any axis binned (a positive, finite width), one centre is the range's low
      // end, (lo - lo) / w = 0, bin 0, and the other its high end, w / w = 1, the last bin; the
      // one split's cost is the two items' own half areas, each times 1, summed in either order,
      // the same number on every such axis. The first axis's is the only one `cost < best` keeps.
      if (count == 2) break;
    }
    if (best_axis < 0) return 0;
    partition(in, first, count, keys_[best_axis].data(), best_bin, best_left, out);
    return best_left;
  }

  // std::stable_partition's order: the items of the bins up to best_bin (`half` of them), then
  // the others, each in their order.
  static void partition(const Items& in, int32_t first, int32_t count, const uint8_t* key,
                        int best_bin, int32_t half, Items& out) {
    int32_t left = first, right = first + half;
    for (int32_t i = 0; i < count; ++i) {
      const int32_t from = first + i;
      const int32_t to = key[i] <= best_bin ? left++ : right++;
      move(in, from, out, to);
    }
  }

  static void move(const Items& in, int32_t from, Items& out, int32_t to) {
    out.ids[to] = in.ids[from];
    out.boxes[to] = in.boxes[from];
    for (int axis = 0; axis < 3; ++axis) out.centre[axis][to] = in.centre[axis][from];
  }

  static int32_t median_split(const Items& in, int32_t first, int32_t count, const Box& centres,
                              Items& out) {
    const Vec3 e = centres.extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    const int32_t half = count / 2;
    std::vector<int32_t> order(count);
    std::iota(order.begin(), order.end(), 0);
    const double* c = in.centre[axis].data() + first;
    const int32_t* ids = in.ids.data() + first;
    std::nth_element(order.begin(), order.begin() + half, order.end(), [&](int32_t a, int32_t b) {
      return c[a] < c[b] || (c[a] == c[b] && ids[a] < ids[b]);
    });
    for (int32_t i = 0; i < count; ++i) move(in, first + order[i], out, first + i);
    return half;
  }

  Items items_[2];
  std::vector<uint8_t> keys_[3];  // the bin along each axis of sah_split's range
};

// Slot c of a node or block: its box, axis by axis. An unused slot gets the empty box.
void set_box(BoxBvh::Node& n, int c, const Box& box) {
  for (int axis = 0; axis < 3; ++axis) {
    n.lo[axis][c] = box.lo[axis];
    n.hi[axis][c] = box.hi[axis];
  }
}

// A leaf's items as blocks of four at the end of `blocks`; returns the slot's reference to them.
int32_t add_leaf(const Binary& leaf, const BinaryBuilder& builder,
                 std::vector<BoxBvh::Node>& blocks) {
  const int32_t first_block = static_cast<int32_t>(blocks.size());
  for (int32_t at = 0; at < leaf.count; at += BoxBvh::kWidth) {
    BoxBvh::Node block{};
    block.size = std::min(BoxBvh::kWidth, leaf.count - at);
    for (int c = 0; c < BoxBvh::kWidth; ++c) {
      const int32_t i = leaf.first + at + c;
      set_box(block, c, c < block.size ? builder.boxes()[i] : Box());
      block.ref[c] = c < block.size ? builder.ids()[i] : 0;
    }
    blocks.push_back(block);
  }
  const int32_t count = static_cast<int32_t>(blocks.size()) - first_block;
  return ~(first_block << BoxBvh::kBlockBits | (count - 1));
}

// The slots of the node of four made of binary node b's subtree: the two children, then the
// largest slot of more than one item replaced by its two children until there are four (the
// order of the tree kept). Returns how many. A slot of at most kLeafItems items is then a leaf:
// splitting such slots while a node has room keeps the small trees' walks (a few blobs, long
// stretches of rays) as selective as before.
int slots_of(const std::vector<Binary>& bin, int32_t b, int32_t (&slots)[BoxBvh::kWidth]) {
  int size = 0;
  if (bin[b].count == 1) {
    slots[size++] = b;  // a tree of one item
  } else {
    slots[size++] = bin[b].left;
    slots[size++] = bin[b].right;
  }
  while (size < BoxBvh::kWidth) {
    int widest = -1;
    double area = -1;
    for (int i = 0; i < size; ++i) {
      const Binary& s = bin[slots[i]];
      const double a = half_area(s.box);
      if (s.count > 1 && (widest < 0 || a > area || std::isnan(a))) {
        widest = i;
        area = a;
      }
    }
    if (widest < 0) break;
    const int32_t w = slots[widest];
    for (int i = size; i > widest + 1; --i) slots[i] = slots[i - 1];
    slots[widest] = bin[w].left;
    slots[widest + 1] = bin[w].right;
    ++size;
  }
  return size;
}

// Binary node b's subtree as nodes of four (slots_of), their leaves' items in blocks.
int32_t collapse(const std::vector<Binary>& bin, int32_t b, const BinaryBuilder& builder,
                 std::vector<BoxBvh::Node>& out, std::vector<BoxBvh::Node>& blocks) {
  int32_t slots[BoxBvh::kWidth];
  const int size = slots_of(bin, b, slots);
  const int32_t index = static_cast<int32_t>(out.size());
  out.emplace_back();
  BoxBvh::Node node{};
  node.size = size;
  for (int c = 0; c < BoxBvh::kWidth; ++c)
    set_box(node, c, c < node.size ? bin[slots[c]].box : Box());
  for (int c = 0; c < node.size; ++c) {
    const Binary& s = bin[slots[c]];
    node.ref[c] =
        s.leaf() ? add_leaf(s, builder, blocks) : collapse(bin, slots[c], builder, out, blocks);
  }
  out[index] = node;
  return index;
}

// Two slots' coordinates along one axis as one value (GCC's vector extension: one SSE2
// register, the x86-64 baseline), so a node's four slots take two of each test's instructions.
using V2 = double __attribute__((vector_size(2 * sizeof(double))));
V2 load(const double* p) {
  V2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
using M2 = decltype(V2{} < V2{});  // a lane all ones where a comparison holds
// Bit c set where lane c holds. SSE2's movemask takes a pair in one instruction; GCC otherwise
// goes through memory lane by lane, a good part of a node's test.
inline int bits(M2 lanes_01, M2 lanes_23) {
#ifdef __SSE2__
  return _mm_movemask_pd(reinterpret_cast<__m128d>(lanes_01)) |
         _mm_movemask_pd(reinterpret_cast<__m128d>(lanes_23)) << 2;
#else
  return (lanes_01[0] != 0) | (lanes_01[1] != 0) << 1 | (lanes_23[0] != 0) << 2 |
         (lanes_23[1] != 0) << 3;
#endif
}
static_assert(BoxBvh::kWidth == 4, "the tests below take a node's slots two at a time");

// The query box's bounds, each in both lanes, made once per query rather than once per node.
struct QueryBox {
  V2 lo[3], hi[3];
  explicit QueryBox(const Box& q) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = V2{q.lo[i], q.lo[i]};
      hi[i] = V2{q.hi[i], q.hi[i]};
    }
  }
};
// Lane l set where slot 2h + l's box overlaps q (closed boxes).
inline M2 overlaps_half(const BoxBvh::Node& n, const QueryBox& q, int h) {
  return (load(n.lo[0] + 2 * h) <= q.hi[0]) & (load(n.hi[0] + 2 * h) >= q.lo[0]) &
         (load(n.lo[1] + 2 * h) <= q.hi[1]) & (load(n.hi[1] + 2 * h) >= q.lo[1]) &
         (load(n.lo[2] + 2 * h) <= q.hi[2]) & (load(n.hi[2] + 2 * h) >= q.lo[2]);
}
// Bit c set where slot c's box overlaps q. A node or block of at most two slots (a blend of two
// soft objects is one such block) leaves the second pair untested: the callers mask it off.
inline int overlaps(const BoxBvh::Node& n, const QueryBox& q) {
  const M2 none{};
  return bits(overlaps_half(n, q, 0), n.size > 2 ? overlaps_half(n, q, 1) : none);
}

// The slab test of the segment a + s (b - a), s in [0, 1], against boxes grown by pad, with the
// reciprocals taken once per query. The slack on s covers the products' rounding, far below what
// pad adds. An axis the segment does not move along compares a's coordinate with the slab
// instead; a NaN (0 times an infinite reciprocal) constrains nothing, as std::min/max keep the
// other operand.
class SegmentTest {
 public:
  SegmentTest(const Vec3& a, const Vec3& b, double pad) : pad_(pad) {
    for (int i = 0; i < 3; ++i) {
      a_[i] = a[i];
      flat_[i] = b[i] - a[i] == 0;
      inv_[i] = flat_[i] ? 0 : 1 / (b[i] - a[i]);
    }
  }
  // Bit c set where the segment meets slot c's box (the second pair untested where the node has
  // at most two slots, as overlaps()).
  int meets(const BoxBvh::Node& n) const {
    M2 hit[2] = {};
    for (int h = 0; h < (n.size > 2 ? 2 : 1); ++h) {
      V2 s0 = {0, 0}, s1 = {1, 1};
      M2 inside = {-1, -1};
      for (int i = 0; i < 3; ++i) {
        const V2 lo = load(n.lo[i] + 2 * h) - pad_, hi = load(n.hi[i] + 2 * h) + pad_;
        if (flat_[i]) {
          inside &= ~((a_[i] < lo) | (a_[i] > hi));
          continue;
        }
        const V2 u = (lo - a_[i]) * inv_[i], v = (hi - a_[i]) * inv_[i];
        // std::min(u, v) and std::max(u, v) lane by lane, keeping their NaN behaviour.
        const V2 near = v < u ? v : u, far = u < v ? v : u;
        s0 = s0 < near ? near : s0;
        s1 = far < s1 ? far : s1;
      }
      hit[h] = inside & (s0 <= s1 + 1e-12);
    }
    return bits(hit[0], hit[1]);
  }

 private:
  double a_[3], inv_[3], pad_;
  bool flat_[3];
};

// A box lies wholly outside the half-space dot(x - apex, n) >= -pad where its corner farthest
// along n does; that corner takes each axis's hi where n is positive, its lo where negative. An
// axis n does not move along adds nothing (a box unbounded along it would add 0 times infinity).
// With a pad per plane the half-spaces need not meet at one point: a prism's sides, each within
// its own reach of `apex` (the shadow rays of a block of points towards a distant light).
class ConeTest {
 public:
  ConeTest(const Vec3& apex, const Vec3 (&normals)[4], const double (&pads)[4]) {
    for (int k = 0; k < 4; ++k) {
      for (int i = 0; i < 3; ++i) {
        const double w = normals[k][i];
        const size_t row = i * sizeof(double) * BoxBvh::kWidth;
        side_[k][i] = w > 0 ? offsetof(BoxBvh::Node, hi) + row : offsetof(BoxBvh::Node, lo) + row;
        const uint64_t moves = w != 0 ? ~uint64_t{0} : 0;
        for (int l = 0; l < 4; ++l) {
          normal_[k][i][l] = w;
          std::memcpy(&moves_[k][i][l], &moves, sizeof moves);
        }
      }
      for (int l = 0; l < 4; ++l) below_[k][l] = -pads[k];
    }
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < 4; ++l) apex_[i][l] = apex[i];
  }
  // Bit c set where slot c's box is inside no plane's outside, two slots at a time. The sides'
  // offsets and the lanes' constants are taken once per query, not at every node, plane and axis
  // with a branch each (meets10 at 640x480: the shadow lists' and camera lists' walks 27.07 ->
  // 22.16 M instructions). An axis a normal does not move along adds +0 (its term masked off, 0
  // times infinity included) where it added nothing: the same sum but for the sign of a zero,
  // which no comparison sees.
  int meets(const BoxBvh::Node& n) const {
    const char* const node = reinterpret_cast<const char*>(&n);
    M2 in[2];
    for (int h = 0; h < 2; ++h) {
      in[h] = M2{-1, -1};
      for (int k = 0; k < 4; ++k) {
        V2 reach = {0, 0};
        for (int i = 0; i < 3; ++i) {
          const V2 side = load(reinterpret_cast<const double*>(node + side_[k][i]) + 2 * h);
          const V2 term = (side - load(apex_[i])) * load(normal_[k][i]);
          reach += reinterpret_cast<V2>(reinterpret_cast<M2>(term) &
                                        reinterpret_cast<M2>(load(moves_[k][i])));
        }
        in[h] &= reach >= load(below_[k]);
      }
    }
    return bits(in[0], in[1]);
  }
  // meets() with the four slots in one AVX2 register: each lane the same operations in the same
  // order. Only where cpu_has_avx2(); compiled for that target alone (not "fma", which would round
  // a product and a sum once where meets() rounds twice).
  __attribute__((target("avx2"))) int meets_four(const BoxBvh::Node& n) const;

 private:
  size_t side_[4][3];  // the byte offset in a node of plane k's farthest side along axis i
  // Each in four lanes: plane k's normal's axis i, the apex's, minus plane k's pad, and all ones
  // where normal k moves along axis i (else zero).
  alignas(32) double normal_[4][3][4];
  alignas(32) double apex_[3][4];
  alignas(32) double below_[4][4];
  alignas(32) double moves_[4][3][4];
};

__attribute__((target("avx2"))) int ConeTest::meets_four(const BoxBvh::Node& n) const {
  const char* const node = reinterpret_cast<const char*>(&n);
  __m256d in = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  for (int k = 0; k < 4; ++k) {
    __m256d reach = _mm256_setzero_pd();
    for (int i = 0; i < 3; ++i) {
      const __m256d side = _mm256_loadu_pd(reinterpret_cast<const double*>(node + side_[k][i]));
      const __m256d term = _mm256_mul_pd(_mm256_sub_pd(side, _mm256_load_pd(apex_[i])),
                                         _mm256_load_pd(normal_[k][i]));
      reach = _mm256_add_pd(reach, _mm256_and_pd(term, _mm256_load_pd(moves_[k][i])));
    }
    // meets()'s reach >= -pad: false where either is a NaN.
    in = _mm256_and_pd(in, _mm256_cmp_pd(reach, _mm256_load_pd(below_[k]), _CMP_GE_OQ));
  }
  return _mm256_movemask_pd(in);
}
}  // namespace

void BoxBvh::build(const std::vector<Box>& boxes, const std::vector<int32_t>& ids) {
  nodes_.clear();
  blocks_.clear();
  std::vector<Box> kept_boxes;
  std::vector<int32_t> kept_ids;
  for (size_t i = 0; i < boxes.size(); ++i)
    if (!boxes[i].empty()) {
      kept_boxes.push_back(boxes[i]);
      kept_ids.push_back(ids[i]);
    }
  if (kept_ids.empty()) return;
  const int32_t count = static_cast<int32_t>(kept_ids.size());
  BinaryBuilder builder(std::move(kept_boxes), std::move(kept_ids));
  if (all_ordered(builder.boxes())) {
    builder.build<true>(0, count, 0);
  } else {
    builder.build<false>(0, count, 0);
  }
  if (count <= kWidth)
    add_leaf(builder.nodes[0], builder, blocks_);
  else
    collapse(builder.nodes, 0, builder, nodes_, blocks_);
  note_order();
}

std::vector<int32_t> BoxBvh::tree_order() const {
  size_t items = 0;
  for (const Node& b : blocks_) items += b.size;
  std::vector<int32_t> out(items);
  walk<false>([](const Node&) { return (1 << kWidth) - 1; }, out.data(), 0);
  return out;
}

void BoxBvh::relabel(const std::vector<int32_t>& to) {
  for (Node& b : blocks_)
    for (int c = 0; c < b.size; ++c) b.ref[c] = to[b.ref[c]];
  note_order();
}

void BoxBvh::note_order() {
  const std::vector<int32_t> order = tree_order();
  ascending_ = std::is_sorted(order.begin(), order.end());
}

template <bool kScattered, class Test>
int BoxBvh::walk(const Test& test, int32_t* out, int count) const {
  if (empty()) return count;
  if (nodes_.empty()) return leaf_items(~0, test, out, count);  // one block: blocks_[0]
  int32_t stack[kStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    const int mask = test(n) & ((1 << n.size) - 1);
    // Nodes pushed last to first are visited left to right; leaves are reported as their node is
    // (last to first). That order, the same for every query, is tree_order().
    for (int c = n.size - 1; c >= 0; --c) {
      const int32_t ref = n.ref[c];
      const int passed = mask >> c & 1;
      // Which slots pass a scattered query is no pattern a branch predicts, so there a node is
      // pushed but counted only where it passed. A passing leaf's items are written the same way
      // in every walk: an item that did not pass is written where the next item will go, never
      // past the room for all items (it is one not yet reported).
      if (ref >= 0) {
        if (!kScattered && !passed) continue;
        stack[top] = ref;
        top += passed;
        continue;
      }
      if (passed) count = leaf_items(ref, test, out, count);
    }
  }
  return count;
}

// Inline in the walk: out of line (GCC's choice once the cone's test held its constants), each
// call copied the test's loop-invariant constants to the stack again, 94 instructions for every
// passing leaf (meets10 at 640x480: 25,705 calls; callgrind, whole process, 600.73 -> 598.10 M,
// meets1 248.23 -> 246.38 M, pov:golfball at 320x240 373.48 -> 373.04 M).
template <class Test>
[[gnu::always_inline]] inline int BoxBvh::leaf_items(int32_t ref, const Test& test, int32_t* out,
                                                     int count) const {
  const Node* block = &blocks_[~ref >> kBlockBits];
  for (const Node* end = block + (~ref & ((1 << kBlockBits) - 1)) + 1; block != end; ++block) {
    const int items = test(*block) & ((1 << block->size) - 1);
    for (int i = 0; i < block->size; ++i) {
      out[count] = block->ref[i];
      count += items >> i & 1;
    }
  }
  return count;
}

int BoxBvh::query(const Box& q, int32_t* out, int count) const {
  const QueryBox box(q);
  const int end = walk<true>([&](const Node& n) { return overlaps(n, box); }, out, count);
  // Children are combined in their compiled order, so results do not depend on the query.
  if (!ascending_) std::sort(out + count, out + end);
  return end;
}

int BoxBvh::query(const Box& q, const Vec3& a, const Vec3& b, double pad, int32_t* out,
                  int count) const {
  const SegmentTest segment(a, b, pad);
  const QueryBox box(q);
  const int end =
      walk<false>([&](const Node& n) { return overlaps(n, box) & segment.meets(n); }, out, count);
  if (!ascending_) std::sort(out + count, out + end);
  return end;
}

int BoxBvh::segment_items(const Vec3& a, const Vec3& b, double pad, int32_t* out) const {
  const SegmentTest segment(a, b, pad);
  return walk<false>([&](const Node& n) { return segment.meets(n); }, out, 0);
}

int BoxBvh::cone_items(const Vec3& apex, const Vec3 (&normals)[4], double pad, int32_t* out) const {
  const double pads[4] = {pad, pad, pad, pad};
  return cone_items(apex, normals, pads, out);
}

int BoxBvh::cone_items(const Vec3& apex, const Vec3 (&normals)[4], const double (&pads)[4],
                       int32_t* out) const {
  return cone_items(apex, normals, pads, out,
                    cpu_has_avx2() ? ConeLanes::kFour : ConeLanes::kPairs);
}

int BoxBvh::cone_items(const Vec3& apex, const Vec3 (&normals)[4], const double (&pads)[4],
                       int32_t* out, ConeLanes lanes) const {
  const ConeTest cone(apex, normals, pads);
  // Four slots at once: a node's test is a call (meets_four is not inlined into this code, built
  // for the baseline) of about half the instructions of the pairs' test inline (callgrind, whole
  // process, 1 thread, 640x480: meets10 598.09 -> 590.28 M, meets1 246.37 -> 240.63 M).
  if (lanes == ConeLanes::kFour)
    return walk<false>([&](const Node& n) { return cone.meets_four(n); }, out, 0);
  return walk<false>([&](const Node& n) { return cone.meets(n); }, out, 0);
}

}  // namespace softtrace

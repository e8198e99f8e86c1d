// The pruning hierarchy (fieldlib/bvh.h) reports exactly the items a test of every item's box
// would: boxes that overlap a query box, boxes (grown by a pad) a segment meets, both together.
// The reference below is the plain scalar test, with its own branch for axes a segment does not
// move along; the hierarchy's vectorised test has none and must agree with it bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "math/bvh.h"
#include "math/cpu_avx2.h"

namespace softtrace::test {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool overlaps(const Box& a, const Box& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
         a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

bool segment_meets(const Vec3& a, const Vec3& b, double pad, const Box& box) {
  double s0 = 0, s1 = 1;
  for (int i = 0; i < 3; ++i) {
    const double lo = box.lo[i] - pad, hi = box.hi[i] + pad, e = b[i] - a[i];
    if (e == 0) {
      if (a[i] < lo || a[i] > hi) return false;
      continue;
    }
    const double u = (lo - a[i]) * (1 / e), v = (hi - a[i]) * (1 / e);
    s0 = std::max(s0, std::min(u, v));
    s1 = std::min(s1, std::max(u, v));
  }
  return s0 <= s1 + 1e-12;
}

struct Items {
  std::vector<Box> boxes;
  std::vector<int32_t> ids;
  BoxBvh bvh;
  void build() { bvh.build(boxes, ids); }
};

// Boxes in [-10, 10]^3 of many sizes, with points, flat boxes, exact duplicates, boxes unbounded
// on one side, and empty ones (never reported); ids in no particular order.
Items random_items(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-10, 10), size(0, 1);
  Items items;
  for (int i = 0; i < n; ++i) {
    const Vec3 centre{c(rng), c(rng), c(rng)};
    const double s = std::pow(10.0, 3 * size(rng) - 2);
    Vec3 half{s * size(rng), s * size(rng), s * size(rng)};
    if (i % 17 == 3) half = {};
    if (i % 13 == 5) half.y = 0;
    Box b(centre - half, centre + half);
    if (i % 29 == 7) b.lo.x = -kInf;
    if (i % 31 == 11) b.hi.z = kInf;
    if (i % 37 == 13) b = Box();
    if (i % 41 == 17 && i > 0) b = items.boxes.back();
    items.boxes.push_back(b);
    items.ids.push_back((i * 7919) % (n + 1));
  }
  items.build();
  return items;
}

std::vector<int32_t> sorted(std::vector<int32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// The three queries against the scalar tests of every item, for random boxes and segments:
// axis-aligned and zero-length ones, and ones starting on an item's corner or face.
void check_against_scan(const Items& items, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-12, 12), r(0, 3);
  const int n = static_cast<int>(items.boxes.size());
  std::vector<int32_t> out(n + 1);  // the first query writes after one entry of its own
  for (int q = 0; q < 600; ++q) {
    const Vec3 p{c(rng), c(rng), c(rng)};
    const Box box = Box::around(p, r(rng));
    Vec3 a = p, b{c(rng), c(rng), c(rng)};
    if (q % 5 == 1) b = {a.x, a.y, b.z};  // moves along z only
    if (q % 5 == 2) b = a;                // a point
    if (q % 7 == 3 && !items.boxes[q % n].empty()) {
      a = items.boxes[q % n].lo;  // on a corner (or an infinite coordinate: skipped)
      b = {a.x + r(rng), a.y, a.z};
      if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(a.z)) continue;
    }
    const double pad = q % 3 == 0 ? 0 : 1e-3;
    const Box around_segment(Vec3{std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)},
                             Vec3{std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)});
    const Box q_box = q % 2 ? box : around_segment;

    std::vector<int32_t> want_box, want_segment, want_both;
    for (int i = 0; i < n; ++i) {
      const Box& item = items.boxes[i];
      if (item.empty()) continue;
      const bool in_box = overlaps(item, q_box), meets = segment_meets(a, b, pad, item);
      if (in_box) want_box.push_back(items.ids[i]);
      if (meets) want_segment.push_back(items.ids[i]);
      if (in_box && meets) want_both.push_back(items.ids[i]);
    }
    std::sort(want_box.begin(), want_box.end());
    std::sort(want_both.begin(), want_both.end());

    // The box queries return ids sorted, after whatever the caller had written before them.
    out[0] = -5;
    int end = items.bvh.query(q_box, out.data(), 1);
    ASSERT_EQ(out[0], -5);
    EXPECT_EQ(std::vector<int32_t>(out.begin() + 1, out.begin() + end), want_box) << "query " << q;
    end = items.bvh.query(q_box, a, b, pad, out.data(), 0);
    EXPECT_EQ(std::vector<int32_t>(out.begin(), out.begin() + end), want_both) << "query " << q;
    end = items.bvh.segment_items(a, b, pad, out.data());
    EXPECT_EQ(sorted({out.begin(), out.begin() + end}), sorted(want_segment)) << "query " << q;
  }
}

}  // namespace

TEST(BoxBvh, ReportsExactlyTheItemsAScanFinds) {
  // Up to four items the root is a leaf (one block); five need a node above.
  for (int n : {1, 2, 3, 4, 5, 64, 700}) check_against_scan(random_items(n, 3 + n), 11 + n);
}

// Equal centres leave the surface-area heuristic nothing to split; boxes nested like onion
// layers make it cut one item at a time, so the tree's depth must be capped for the walk's stack.
// cone_items against the scalar test of every item's farthest corner along each plane's normal,
// in the order of the tree: pyramids from random apexes, some with a normal along an axis or
// across one (a shadow prism's sides: u is across the axis least aligned with the light), so a
// box unbounded along such an axis is neither kept nor dropped by a 0 times infinity; some with a
// pad per plane; in both of the node test's forms (two slots at a time, and four with AVX2 where
// the CPU has it).
TEST(BoxBvh, ConeItemsAreTheScansInTreeOrder) {
  const Items items = random_items(700, 17);
  const std::vector<int32_t> order = items.bvh.tree_order();
  std::vector<int32_t> out(items.boxes.size());
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> c(-12, 12), u(-1, 1);
  int kept = 0, dropped = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 apex{c(rng), c(rng), c(rng)};
    Vec3 normals[4];
    for (Vec3& n : normals) n = normalize({u(rng), u(rng), u(rng)});
    if (q % 3 == 0) normals[q % 4] = {0, 0, q % 2 ? 1.0 : -1.0};
    if (q % 3 == 1) {
      normals[q % 4][q % 5 % 3] = 0;
      normals[q % 4] = normalize(normals[q % 4]);
      normals[(q + 1) % 4] = -normals[q % 4];
    }
    const double pad = q % 2 ? 0 : 1e-6;
    double pads[4] = {pad, pad, pad, pad};
    if (q % 4 == 1)
      for (double& p : pads) p = 2 * (u(rng) + 1);
    std::vector<bool> in(items.ids.size() + 1, false);  // by id
    for (size_t i = 0; i < items.boxes.size(); ++i) {
      const Box& b = items.boxes[i];
      if (b.empty()) continue;
      bool inside = true;
      for (int p = 0; p < 4; ++p) {
        const Vec3& n = normals[p];
        double reach = 0;
        for (int k = 0; k < 3; ++k)
          if (n[k] != 0) reach += ((n[k] > 0 ? b.hi[k] : b.lo[k]) - apex[k]) * n[k];
        inside = inside && reach >= -pads[p];
      }
      if (inside) in[items.ids[i]] = true;
    }
    std::vector<int32_t> want;
    for (const int32_t id : order)
      if (in[id]) want.push_back(id);
    const int end = q % 4 == 1 ? items.bvh.cone_items(apex, normals, pads, out.data())
                               : items.bvh.cone_items(apex, normals, pad, out.data());
    EXPECT_EQ(std::vector<int32_t>(out.begin(), out.begin() + end), want) << "query " << q;
    // Each of the node test's two forms, whichever the overloads above chose.
    const int pairs =
        items.bvh.cone_items(apex, normals, pads, out.data(), BoxBvh::ConeLanes::kPairs);
    EXPECT_EQ(std::vector<int32_t>(out.begin(), out.begin() + pairs), want) << "query " << q;
    if (cpu_has_avx2()) {
      const int four =
          items.bvh.cone_items(apex, normals, pads, out.data(), BoxBvh::ConeLanes::kFour);
      EXPECT_EQ(std::vector<int32_t>(out.begin(), out.begin() + four), want) << "query " << q;
    }
    kept += end;
    dropped += static_cast<int>(order.size()) - end;
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(dropped, 0);
}

TEST(BoxBvh, DegenerateSetsStillSplit) {
  Items same;
  for (int i = 0; i < 300; ++i) {
    same.boxes.push_back(Box::around({1, 2, 3}, 1 + (i % 3)));
    same.ids.push_back(i);
  }
  same.build();
  check_against_scan(same, 5);

  Items onion;
  for (int i = 0; i < 3000; ++i) {
    const double s = std::pow(1.01, i);
    onion.boxes.push_back(Box({-s, -s, -s}, {s, 2 * s, s}));
    onion.ids.push_back(i);
  }
  onion.build();
  check_against_scan(onion, 6);
}

// A tree relabelled by its own order (as a large sum is compiled) meets its items in ascending
// order, so the queries skip their sort: the scan still agrees.
TEST(BoxBvh, RelabelledByItsOrderStillReportsWhatAScanFinds) {
  Items items = random_items(500, 21);
  const std::vector<int32_t> order = items.bvh.tree_order();
  std::vector<int32_t> all_ids;
  for (size_t i = 0; i < items.boxes.size(); ++i)
    if (!items.boxes[i].empty()) all_ids.push_back(items.ids[i]);
  ASSERT_EQ(sorted(order), sorted(all_ids));
  std::vector<int32_t> position(items.boxes.size() + 1, -1);
  for (size_t k = 0; k < order.size(); ++k) position[order[k]] = static_cast<int32_t>(k);
  for (int32_t& id : items.ids) id = position[id];
  items.bvh.relabel(position);
  const std::vector<int32_t> relabelled = items.bvh.tree_order();
  for (size_t k = 0; k < relabelled.size(); ++k) ASSERT_EQ(relabelled[k], static_cast<int32_t>(k));
  check_against_scan(items, 22);
}

// The trees themselves, not only their answers: the order of the items and two queries' lists
// over 400 sets (2 to 3,000 boxes; flat, equal centres, half-infinite and unbounded boxes), hashed
// (FNV-1a). The value is the build's of 2a904fc, before the split sweeps over per-axis centres and
// stopped after one axis for two items: a build that changes any split, or the order of a
// partition, changes the hash. A deliberate change of the tree must say so and set a new value.
// FNV-1a over a set's tree: the order of its items and a box query's list.
struct TreeHash {
  uint64_t hash = 0xcbf29ce484222325ULL;
  std::vector<int32_t> out;

  void mix(uint64_t v) {
    for (int b = 0; b < 8; ++b) hash = (hash ^ ((v >> (8 * b)) & 0xff)) * 0x100000001b3ULL;
  }
  BoxBvh add_tree(const std::vector<Box>& boxes, const std::vector<int32_t>& ids) {
    BoxBvh bvh;
    bvh.build(boxes, ids);
    for (const int32_t id : bvh.tree_order()) mix(static_cast<uint64_t>(id));
    out.assign(boxes.size(), 0);
    const int k = bvh.query(Box({-5, -5, -5}, {5, 5, 5}), out.data(), 0);
    for (int i = 0; i < k; ++i) mix(static_cast<uint64_t>(out[i]));
    return bvh;
  }
};

uint64_t tree_fingerprint() {
  TreeHash h;
  for (int set = 0; set < 400; ++set) {
    std::mt19937_64 rng(1000 + set);
    const auto unit = [&] { return static_cast<double>(rng() >> 11) * 0x1p-53; };
    const int n = set < 100 ? 2 + set % 7 : 1 + static_cast<int>(rng() % 3000);
    std::vector<Box> boxes;
    std::vector<int32_t> ids;
    for (int i = 0; i < n; ++i) {
      Vec3 c{40 * unit() - 20, 40 * unit() - 20, 40 * unit() - 20};
      if (set % 5 == 1) c.z = 0;
      if (set % 7 == 2 && i % 3 == 0) c = {1, 2, 3};
      Box b = Box::around(c, 0.1 + 5 * unit() * unit());
      if (set % 11 == 3 && i % 29 == 0) b.hi.x = kInf;
      if (set % 13 == 4 && i % 31 == 0) b = Box::unbounded();
      boxes.push_back(b);
      ids.push_back(static_cast<int32_t>((i * 7919) % n));
    }
    const BoxBvh bvh = h.add_tree(boxes, ids);
    const Vec3 normals[4] = {{1, 0.1, 0}, {-1, 0.1, 0}, {0.1, 1, 0}, {0.1, -1, 0}};
    const int m = bvh.cone_items({0, 0, -30}, normals, 0.5, h.out.data());
    for (int i = 0; i < m; ++i) h.mix(static_cast<uint64_t>(h.out[i]));
    h.mix(0xffffffffULL);
  }
  return h.hash;
}

TEST(BoxBvh, TheTreesAreTheSameAsBefore) {
  EXPECT_EQ(tree_fingerprint(), 0xad5e317d1acef113ULL);
}

// The build unites boxes whose lo lies below their hi on every axis by their los' minimum and
// their his' maximum alone; any other set takes the full union. Sets with flat boxes (lo = hi on
// an axis, zeros of either sign among them), NaN coordinates and infinite ones, hashed as above:
// the value is the build's before that shortcut (d0921e0), so a set that took it wrongly (a NaN
// box's bins and costs differ) changes the hash.
uint64_t unordered_fingerprint() {
  TreeHash h;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int set = 0; set < 60; ++set) {
    std::mt19937_64 rng(5000 + set);
    const auto unit = [&] { return static_cast<double>(rng() >> 11) * 0x1p-53; };
    const int n = 2 + static_cast<int>(rng() % 600);
    std::vector<Box> boxes;
    std::vector<int32_t> ids;
    for (int i = 0; i < n; ++i) {
      const Vec3 c{40 * unit() - 20, 40 * unit() - 20, 40 * unit() - 20};
      Box b = Box::around(c, 0.1 + 5 * unit() * unit());
      if (i % 7 == set % 7) b.lo.y = b.hi.y;  // flat along y
      if (i % 11 == 1) b.lo.z = b.hi.z = set % 2 ? 0.0 : -0.0;
      if (set % 3 == 0 && i % 13 == 2) b.lo.x = nan;
      if (set % 3 == 1 && i % 17 == 3) b.hi.y = nan;
      if (set % 5 == 2 && i % 19 == 4) b.hi.x = kInf;
      boxes.push_back(b);
      ids.push_back(static_cast<int32_t>((i * 7919) % n));
    }
    h.add_tree(boxes, ids);
    h.mix(0xffffffffULL);
  }
  return h.hash;
}

TEST(BoxBvh, TheTreesOfFlatAndNaNBoxesAreTheSameAsBefore) {
  EXPECT_EQ(unordered_fingerprint(), 0x9f3ea5dbb5a251beULL);
}

TEST(BoxBvh, EmptyHasNothing) {
  Items none;
  none.boxes = {Box(), Box()};
  none.ids = {0, 1};
  none.build();
  EXPECT_TRUE(none.bvh.empty());
  int32_t out[2];
  EXPECT_EQ(none.bvh.query(Box::unbounded(), out, 0), 0);
  EXPECT_EQ(none.bvh.segment_items({0, 0, 0}, {1, 1, 1}, 0, out), 0);
}

}  // namespace softtrace::test

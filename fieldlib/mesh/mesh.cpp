// The mesher's three passes: find the leaf blocks that may hold the surface (intervals over a
// tree of blocks), mesh each leaf (leaf.cpp), weld the vertices that neighbouring leaves share.
// Work is handed out in a fixed order and gathered by index, so the mesh does not depend on the
// number of threads.
#include "mesh/mesh.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "mesh/blob_bounds.h"
#include "mesh/leaf.h"

namespace softtrace {
namespace {

constexpr int kTopCells = 64;     // the side of the blocks the tree starts from, at least
constexpr long kMaxTops = 32768;  // top blocks at most: a finer lattice starts from larger ones

struct Block {
  int lo[3], hi[3];  // cells [lo, hi) per axis
};

// Runs job(i, scratch) for i < count on `threads` threads, each with its own Scratch; rethrows
// the first exception.
template <class Scratch = SamplerScratch, class Job>
void parallel_for(size_t count, int threads, const std::atomic<bool>* cancel, Job job) {
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    Scratch scratch;
    try {
      for (size_t i; (i = next++) < count;) {
        if (cancel && cancel->load(std::memory_order_relaxed)) throw MeshCancelled();
        job(i, scratch);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  const size_t extra = std::min<size_t>(size_t(std::max(threads, 1)) - 1, count);
  for (size_t t = 1; t <= extra; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// Frees a vector's storage now: `v = {}` would not (it assigns an empty initializer list, which
// keeps the capacity), and the weld's arrays would be held to the end.
template <class T, class A>
void release(std::vector<T, A>& v) {
  std::vector<T, A>().swap(v);
}

Lattice make_lattice(const Box& region, const MeshOptions& o) {
  if (!region.bounded()) throw std::invalid_argument("the region to mesh is not a bounded box");
  const Vec3 ext = region.extent();
  const double longest = std::max({ext.x, ext.y, ext.z});
  if (!(o.voxel > 0) && !(o.cells > 0))
    throw std::invalid_argument("the voxel size or the number of cells must be positive");
  const double h = o.voxel > 0 ? o.voxel : longest / o.cells;
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("the voxel size must be positive and finite (the region is " +
                                std::string(longest > 0 ? "too large)" : "flat)"));
  Lattice l;
  l.h = h;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil(ext[a] / h * (1 - 1e-12));
    if (!(cells <= kMaxCells))
      throw std::invalid_argument("the lattice would have more than " + std::to_string(kMaxCells) +
                                  " cells along an axis; choose a larger voxel");
    l.n[a] = std::max(1, int(cells));
  }
  const Vec3 half{l.n[0] * h * 0.5, l.n[1] * h * 0.5, l.n[2] * h * 0.5};
  l.box = {region.center() - half, region.center() + half};
  return l;
}

// A leaf's side in cells: 8 where a sum of blobs is sampled in closed form (fewer leaves, fewer
// shared faces to weld and fewer blocks to bound outweigh the corners of empty cells: at 256^3 on
// the 1000 blobs, 4 took 1.12x the CPU time of 8, and 16 took 1.6x); 4 where the evaluators walk
// the program (a corner costs more there).
int leaf_cells(const FieldSampler& sampler) {
  return sampler.batch() > kBatch ? 8 : 4;
}

// What the search for leaves reads: the field, and for a sum of balls and ellipsoids its blobs,
// bounded in closed form (blob_bounds.h) with the blobs of each level of blocks kept per depth.
struct LeafSearch {
  const MeshField& field;
  const Lattice& lattice;
  int leaf_cells;
  const BlobSum* blobs;                  // null: the box evaluator bounds the blocks
  std::vector<std::vector<int32_t>> at;  // at[d]: the blobs of the block at depth d
};

// The leaves of `b` that may hold the surface, in a fixed order. A block whose interval lies
// wholly on one side holds none, unless it is inside and reaches the padding, where the cap is.
// The interval is widened by a relative 1e-9 so that the rounding of the points' values cannot
// contradict a block that was skipped.
void find_leaves(LeafSearch& search, const Block& b, size_t depth, Workspace& ws,
                 std::vector<Block>* leaves) {
  const MeshField& field = search.field;
  const Lattice& l = search.lattice;
  const int pmax[3] = {b.hi[0], b.hi[1], b.hi[2]};  // the block's last points
  const Box box = l.span(b.lo, pmax);
  Interval v;
  if (search.blobs) {
    if (search.at.size() < depth + 2) search.at.resize(depth + 2);
    const std::vector<int32_t>& parent = search.at[depth];
    search.at[depth + 1].clear();
    v = blob_interval(*search.blobs, parent.data(), int(parent.size()), box, &search.at[depth + 1]);
  } else {
    ws.fit(*field.program);
    v = bounds(*field.program, box, ws).value;
  }
  const double margin = 1e-9 * (1 + std::abs(field.iso) + std::max(std::abs(v.lo), std::abs(v.hi)));
  const bool above = v.lo > field.iso + margin, below = v.hi < field.iso - margin;
  const bool in = field.inside_sign > 0 ? above : below;
  const bool out = field.inside_sign > 0 ? below : above;
  bool padding = false;
  for (int a = 0; a < 3; ++a) padding |= b.lo[a] == 0 || b.hi[a] == l.n[a] + 1;
  if (out || (in && !padding)) return;
  bool leaf = true;
  for (int a = 0; a < 3; ++a) leaf &= b.hi[a] - b.lo[a] <= search.leaf_cells;
  if (leaf) {
    leaves->push_back(b);
    return;
  }
  // Halves on leaf boundaries, so that every leaf is a cell of the leaf_cells grid.
  const int cells = search.leaf_cells;
  int mid[3];
  for (int a = 0; a < 3; ++a) {
    const int size = b.hi[a] - b.lo[a];
    mid[a] = size <= cells ? b.hi[a] : b.lo[a] + (size / 2 + cells - 1) / cells * cells;
  }
  for (int c = 0; c < 8; ++c) {
    Block child;
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      child.lo[a] = c >> a & 1 ? mid[a] : b.lo[a];
      child.hi[a] = c >> a & 1 ? b.hi[a] : mid[a];
      empty |= child.lo[a] >= child.hi[a];
    }
    if (!empty) find_leaves(search, child, depth + 1, ws, leaves);
  }
}

}  // namespace

Mesh mesh(const MeshField& field, const Box& region, const MeshOptions& options) {
  const Lattice lattice = make_lattice(region, options);
  auto report = [&](double fraction) {
    if (options.progress) options.progress(fraction);
  };

  // Pass 1: the tree of blocks, from top blocks of `top` cells (cells 0..n along each axis).
  std::vector<Block> tops;
  const int cells[3] = {lattice.n[0] + 1, lattice.n[1] + 1, lattice.n[2] + 1};
  int top = kTopCells;
  auto count = [&](int t) {
    long c = 1;
    for (int a = 0; a < 3; ++a) c *= (cells[a] + t - 1) / t;
    return c;
  };
  while (count(top) > kMaxTops) top *= 2;
  for (int k = 0; k < cells[2]; k += top)
    for (int j = 0; j < cells[1]; j += top)
      for (int i = 0; i < cells[0]; i += top)
        tops.push_back({{i, j, k},
                        {std::min(i + top, cells[0]), std::min(j + top, cells[1]),
                         std::min(k + top, cells[2])}});
  const FieldSampler sampler(*field.program);
  const BlobSum* blobs =
      sampler.blobs() && blob_intervals_apply(*sampler.blobs()) ? sampler.blobs() : nullptr;
  std::vector<std::vector<Block>> found(tops.size());
  std::atomic<size_t> tops_done{0};
  parallel_for(tops.size(), options.threads, options.cancel, [&](size_t i, SamplerScratch& s) {
    LeafSearch search{field, lattice, leaf_cells(sampler), blobs, {}};
    if (blobs) {  // the blobs of the top block: those whose support boxes meet it
      const int pmax[3] = {tops[i].hi[0], tops[i].hi[1], tops[i].hi[2]};
      search.at.resize(1);
      search.at[0].resize(size_t(blobs->size()));
      search.at[0].resize(size_t(field.program->groups[size_t(blobs->group())].bvh.query(
          lattice.span(tops[i].lo, pmax), search.at[0].data(), 0)));
    }
    find_leaves(search, tops[i], 0, s.ws, &found[i]);
    report(0.1 * double(++tops_done) / double(tops.size()));
  });
  std::vector<Block> leaves;
  for (const auto& f : found) leaves.insert(leaves.end(), f.begin(), f.end());
  release(found);

  // Pass 2: the leaves, each on its own.
  std::vector<LeafMesh> parts(leaves.size());
  std::atomic<size_t> leaves_done{0};
  struct LeafWorker {
    SamplerScratch scratch;
    std::optional<LeafMesher> mesher;
  };
  parallel_for<LeafWorker>(leaves.size(), options.threads, options.cancel,
                           [&](size_t i, LeafWorker& w) {
                             if (!w.mesher) w.mesher.emplace(field, sampler, lattice);
                             w.mesher->run(leaves[i].lo, leaves[i].hi, w.scratch, &parts[i]);
                             report(0.1 + 0.8 * double(++leaves_done) / double(leaves.size()));
                           });

  // Pass 3: weld. A vertex on a leaf's boundary is in the neighbours too, with the same key; the
  // first in leaf order names it, and its position is the one leaf's that solved it.
  // Interior vertices are unique already.
  std::vector<size_t> first(parts.size() + 1, 0);
  for (size_t i = 0; i < parts.size(); ++i) first[i + 1] = first[i] + parts[i].keys.size();
  auto part_of = [&](uint64_t g) {
    return size_t(std::upper_bound(first.begin(), first.end(), g) - first.begin()) - 1;
  };
  // The boundary vertices, (key, vertex before welding), sorted by key on two threads with no
  // merge after: the keys below a pivot (the median of every kSampleEvery-th key) and the others
  // are written to the two ends of one array, and each end is sorted on its own. The pairs are
  // distinct, so the sorted order is one for any pivot and thread count.
  constexpr size_t kPartChunk = 256;
  constexpr size_t kSampleEvery = 64;
  const size_t part_chunks = (parts.size() + kPartChunk - 1) / kPartChunk;
  auto chunk_parts = [&](size_t c) {
    return std::make_pair(c * kPartChunk, std::min(parts.size(), (c + 1) * kPartChunk));
  };
  auto for_boundary = [&](size_t c, auto visit) {
    const auto [begin, end] = chunk_parts(c);
    for (size_t i = begin; i < end; ++i)
      for (size_t v = 0; v < parts[i].keys.size(); ++v)
        if (parts[i].place[v] != EdgePlace::Interior) visit(parts[i].keys[v], first[i] + v);
  };
  std::vector<std::vector<uint64_t>> samples(part_chunks);
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    size_t seen = 0;
    for_boundary(c, [&](uint64_t key, uint64_t) {
      if (seen++ % kSampleEvery == 0) samples[c].push_back(key);
    });
  });
  std::vector<uint64_t> sample;
  for (const auto& s : samples) sample.insert(sample.end(), s.begin(), s.end());
  release(samples);
  const auto middle = sample.begin() + std::ptrdiff_t(sample.size() / 2);
  std::nth_element(sample.begin(), middle, sample.end());
  const uint64_t pivot = sample.empty() ? 0 : *middle;
  release(sample);
  std::vector<size_t> below_at(part_chunks + 1, 0), above_at(part_chunks + 1, 0);
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    for_boundary(c, [&](uint64_t key, uint64_t) { ++(key < pivot ? below_at : above_at)[c + 1]; });
  });
  for (size_t c = 0; c < part_chunks; ++c) {
    below_at[c + 1] += below_at[c];
    above_at[c + 1] += above_at[c];
  }
  const size_t below = below_at.back();
  struct Shared {
    uint64_t key, vertex;
    bool operator<(const Shared& o) const {
      return key < o.key || (key == o.key && vertex < o.vertex);
    }
  };
  MeshArray<Shared> boundary;  // written by the chunks: not filled first (mesh_array.h)
  boundary.resize(below + above_at.back());
  // The weld's map, the vertex a duplicate stands for (kKeep: none), filled by the same chunks.
  constexpr uint64_t kKeep = ~uint64_t(0);
  MeshArray<uint64_t> same;
  same.resize(first.back());
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    const auto [begin, end] = chunk_parts(c);
    std::fill(same.begin() + std::ptrdiff_t(first[begin]),
              same.begin() + std::ptrdiff_t(first[end]), kKeep);
    size_t lo = below_at[c], hi = below + above_at[c];
    for_boundary(c, [&](uint64_t key, uint64_t g) {
      boundary[key < pivot ? lo++ : hi++] = {key, g};
    });
  });
  const auto split_at = boundary.begin() + std::ptrdiff_t(below);
  parallel_for(2, options.threads, options.cancel, [&](size_t h, SamplerScratch&) {
    if (h == 0) std::sort(boundary.begin(), split_at);
    if (h == 1) std::sort(split_at, boundary.end());
  });
  // Each key's group is welded on its own (it writes only its own vertices): the groups below
  // the pivot on one thread, the others on the other.
  const size_t split = below;
  parallel_for(2, options.threads, options.cancel, [&](size_t h, SamplerScratch&) {
    const size_t stop = h == 0 ? split : boundary.size();
    for (size_t b = h == 0 ? 0 : split, end; b < stop; b = end) {
      const uint64_t name = boundary[b].vertex;
      const Vec3* solved = nullptr;
      for (end = b; end < stop && boundary[end].key == boundary[b].key; ++end) {
        const uint64_t g = boundary[end].vertex;
        const size_t i = part_of(g);
        if (parts[i].place[g - first[i]] == EdgePlace::Solved)
          solved = &parts[i].positions[g - first[i]];
        if (end > b) same[g] = name;
      }
      if (!solved)  // the leaves below hold every boundary edge (leaf.h): a broken invariant
        throw std::logic_error("mesh: a boundary vertex that no leaf solved");
      const size_t i = part_of(name);
      parts[i].positions[name - first[i]] = *solved;
    }
  });
  release(boundary);
  // The welded vertices and the faces, numbered in leaf order, written by chunks of leaves on the
  // threads at offsets counted first (the same mesh for any thread count).
  std::vector<size_t> vertex_at(part_chunks + 1, 0), face_at(part_chunks + 1, 0);
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    const auto [begin, end] = chunk_parts(c);
    for (size_t g = first[begin]; g < first[end]; ++g) vertex_at[c + 1] += same[g] == kKeep;
    for (size_t i = begin; i < end; ++i)
      for (const LeafCut& cut : parts[i].cuts) face_at[c + 1] += cut.quad ? 2 : 1;
  });
  for (size_t c = 0; c < part_chunks; ++c) {
    vertex_at[c + 1] += vertex_at[c];
    face_at[c + 1] += face_at[c];
  }
  if (vertex_at.back() > size_t(UINT32_MAX) || face_at.back() > size_t(UINT32_MAX))
    throw std::length_error("the mesh would have more than 2^32 vertices or faces");
  Mesh m;
  m.lattice = lattice.box;
  m.voxel = lattice.h;
  // The large arrays are sized without being filled (mesh_array.h) and each element written once
  // by the chunks on the threads, which share the first writes to fresh pages.
  MeshArray<uint32_t> index;
  m.vertices.resize(vertex_at.back());
  index.resize(first.back());
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    const auto [begin, end] = chunk_parts(c);
    size_t next = vertex_at[c];
    for (size_t i = begin; i < end; ++i)
      for (size_t v = 0; v < parts[i].keys.size(); ++v) {
        const size_t g = first[i] + v;
        if (same[g] != kKeep) continue;
        index[g] = uint32_t(next);
        m.vertices[next++] = parts[i].positions[v];
      }
  });
  // A duplicate's vertex comes before it in leaf order, in this chunk or an earlier one: its
  // index is known once every chunk above is done.
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    const auto [begin, end] = chunk_parts(c);
    for (size_t g = first[begin]; g < first[end]; ++g)
      if (same[g] != kKeep) index[g] = index[same[g]];
  });
  release(same);
  m.faces.resize(face_at.back());
  // A quadrilateral is split along its shorter diagonal (the better-shaped pair).
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch&) {
    const auto [begin, end] = chunk_parts(c);
    size_t next = face_at[c];
    for (size_t i = begin; i < end; ++i) {
      for (const LeafCut& cut : parts[i].cuts) {
        uint32_t v[4];
        for (int k = 0; k < (cut.quad ? 4 : 3); ++k) v[k] = index[first[i] + cut.v[k]];
        if (!cut.quad) {
          m.faces[next++] = {v[0], v[1], v[2]};
          continue;
        }
        const Vec3 d02 = m.vertices[v[2]] - m.vertices[v[0]];
        const Vec3 d13 = m.vertices[v[3]] - m.vertices[v[1]];
        if (dot(d02, d02) <= dot(d13, d13)) {
          m.faces[next++] = {v[0], v[1], v[2]};
          m.faces[next++] = {v[0], v[2], v[3]};
        } else {
          m.faces[next++] = {v[0], v[1], v[3]};
          m.faces[next++] = {v[1], v[2], v[3]};
        }
      }
      // What the normals need stays: which vertices the leaf solved, and their edges.
      release(parts[i].cuts);
      release(parts[i].keys);
      release(parts[i].positions);
    }
  });

  // Normals, once per welded vertex, by the leaf that solved it: the sampler prepared for the
  // leaf's box (for a sum of blobs, the few blobs there), in chunks of leaves over the threads.
  m.normals.resize(m.vertices.size());  // every welded vertex's, by the one leaf that solved it
  std::atomic<size_t> chunks_done{0};
  parallel_for(part_chunks, options.threads, options.cancel, [&](size_t c, SamplerScratch& s) {
    const auto [begin, end] = chunk_parts(c);
    for (size_t i = begin; i < end; ++i) {
      const int pmax[3] = {leaves[i].hi[0], leaves[i].hi[1], leaves[i].hi[2]};
      sampler.prepare_gradients(lattice.span(leaves[i].lo, pmax), s);
      for (size_t v = 0; v < parts[i].place.size(); ++v) {
        if (parts[i].place[v] == EdgePlace::Borrowed) continue;
        const uint32_t n = index[first[i] + v];
        m.normals[n] = vertex_normal(field, sampler, lattice, m.vertices[n], parts[i].edge[v], s);
      }
      parts[i] = LeafMesh();
    }
    report(0.9 + 0.1 * double(++chunks_done) / double(part_chunks));
  });
  release(parts);
  release(index);
  m.colors.resize(m.vertices.size());
  constexpr size_t kColorChunk = size_t(1) << 16;
  parallel_for(
      (m.colors.size() + kColorChunk - 1) / kColorChunk, options.threads, options.cancel,
      [&](size_t c, SamplerScratch&) {
        const auto begin = m.colors.begin() + std::ptrdiff_t(c * kColorChunk);
        std::fill(begin,
                  begin + std::ptrdiff_t(std::min(kColorChunk, m.colors.size() - c * kColorChunk)),
                  options.color);
      });

  report(1);
  return m;
}

double enclosed_volume(const Mesh& m) {
  // Σ det(a, b, c) / 6 over the faces, relative to the lattice's centre (less cancellation).
  const Vec3 o = m.lattice.empty() ? Vec3{} : m.lattice.center();
  double sum = 0;
  for (const auto& f : m.faces)
    sum += dot(m.vertices[f[0]] - o, cross(m.vertices[f[1]] - o, m.vertices[f[2]] - o));
  return sum / 6;
}

}  // namespace softtrace

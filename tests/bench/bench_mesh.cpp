// Google Benchmark of the mesher (fieldlib/mesh) on the 1000-blob scene of tools/blob_scene.py
// over its bounds, at lattices of N^3 cells on 2 threads: time, and the heap the mesher holds at
// its peak (counted by this executable's operator new), both of which should grow as the
// surface does (N^2), not as the lattice (N^3). Not a test: run build/tests/softtrace_mesh_bench
// (docs/performance.md "Meshing").
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "bench_mesh_scene.h"
#include "mesh/mesh.h"
#include "model/program_builder.h"

namespace {

std::atomic<long> g_live{0}, g_peak{0};

}  // namespace

void* operator new(size_t size) {
  void* p = std::malloc(size ? size : 1);
  if (!p) throw std::bad_alloc();
  const long now = g_live += long(malloc_usable_size(p));
  for (long peak = g_peak; now > peak && !g_peak.compare_exchange_weak(peak, now);) {
  }
  return p;
}
void operator delete(void* p) noexcept {
  if (p) g_live -= long(malloc_usable_size(p));
  std::free(p);
}
void operator delete(void* p, size_t) noexcept {
  operator delete(p);
}

namespace softtrace {
namespace {

void BM_MeshBlobs1000(benchmark::State& state) {
  const SceneObject& o = mesh_bench_blobs().objects.front();
  const Program p = compile(*o.field);
  MeshOptions opt;
  opt.cells = int(state.range(0));
  opt.threads = 2;
  size_t faces = 0, vertices = 0;
  long peak = 0;
  for (auto _ : state) {
    const long before = g_live;
    g_peak = before;
    const Mesh m = mesh({&p, o.iso, o.inside_sign}, o.bounds, opt);
    peak = std::max(peak, long(g_peak) - before);
    faces = m.faces.size();
    vertices = m.vertices.size();
  }
  state.counters["faces"] = double(faces);
  state.counters["vertices"] = double(vertices);
  state.counters["peak_MB"] = double(peak) / 1e6;
}
BENCHMARK(BM_MeshBlobs1000)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace softtrace

BENCHMARK_MAIN();

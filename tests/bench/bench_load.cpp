// Google Benchmark of loading a scene of N blob components (issue 30's target: 1000 components
// load in under 5 ms): the JSON text parsed and every node built (`parse_scene`), and then the
// traced objects compiled (programs, the blobs' BVH). The text is what tools/blob_scene.py N
// writes: murakami spheres in a cube of side 40, indented by one space, numbers of 6 decimals.
// BM_LoadSceneFile times a scene file of your choosing (SOFTTRACE_BENCH_SCENE=path) from its bytes
// on disk to a scene ready to trace: read, parsed, every node built and checked, the traced
// objects compiled (programs, the blobs' BVH), every object's tracer and the Embree scene made,
// as `softtrace render` makes them before its first ray.
// Not a test: run build/tests/softtrace_bench --benchmark_filter=Load.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <random>

#include "render/frame.h"
#include "scene/scene.h"
#include "scene/traced_objects.h"

namespace softtrace {
namespace {

std::string blob_scene_text(int n) {
  using json = nlohmann::json;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-20, 20);
  const double radius = 12.0 * std::cbrt(1000.0 / n) * 0.5;
  json children = json::array();
  for (int i = 0; i < n; ++i) {
    json c = json::array();
    for (int k = 0; k < 3; ++k) c.push_back(std::round(u(rng) * 1e6) / 1e6);
    children.push_back(
        {{"type", "soft_object"},
         {"potential", {{"type", "murakami"}}},
         {"distance", {{"type", "lp_metric"}, {"radii", {radius, radius, radius}}, {"n", 2}}},
         {"translate", c}});
  }
  const json scene = {
      {"camera", {{"eye", {70, -95, 60}}, {"target", {0, 0, 0}}, {"up", {0, 0, 1}}, {"fov", 30}}},
      {"image", {{"width", 640}, {"height", 480}, {"spp", 1}}},
      {"objects",
       {{{"name", "blobs"},
         {"iso", 0.5},
         {"field", {{"type", "soft_blend"}, {"children", children}}}}}}};
  return scene.dump(1);
}

void BM_LoadScene(benchmark::State& state) {
  const std::string text = blob_scene_text(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(parse_scene(text, "blobs.json"));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(text.size()));
}
BENCHMARK(BM_LoadScene)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_LoadAndCompileScene(benchmark::State& state) {
  const std::string text = blob_scene_text(int(state.range(0)));
  for (auto _ : state) {
    const Scene scene = parse_scene(text, "blobs.json");
    benchmark::DoNotOptimize(traced_objects(scene));
  }
}
BENCHMARK(BM_LoadAndCompileScene)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_LoadSceneFile(benchmark::State& state) {
  const char* path = std::getenv("SOFTTRACE_BENCH_SCENE");
  if (!path) {
    state.SkipWithError("set SOFTTRACE_BENCH_SCENE to a scene file");
    return;
  }
  for (auto _ : state) {
    const Scene scene = load_scene(path);
    const TracedScene traced(scene, LipschitzMode::Local);
    benchmark::DoNotOptimize(&traced);
  }
}
BENCHMARK(BM_LoadSceneFile)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace softtrace

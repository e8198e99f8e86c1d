// Google Benchmark microbenchmarks of field evaluation and of the tracer's first-hit search.
// Not a test: run build/tests/softtrace_bench (see README "Benchmarks").
#include <benchmark/benchmark.h>

#include <random>

#include "tracer.h"

namespace softtrace {
namespace {

struct Model {
  const char* name;
  const char* object;  // one scene object
};

const Model kModels[] = {
    {"fig12b_soft_blend",
     R"({"field":{"type":"soft_blend","children":[
          {"type":"soft_object","distance":{"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20}},
          {"type":"soft_object","distance":{"type":"lp_metric","radii":[30,30,12],"n":20}}]}})"},
    {"bt_conic_cylinders",
     R"({"convention":"zero","field":{"type":"bt_union","base":"conic","r1":2,"r2":2,"p":0,"m":[1,2],
          "children":[
            {"type":"offset","scale":4,"children":[{"type":"superelliptic_cylinder","radii":[4,4,4],"n":2,"half_length":12}]},
            {"type":"offset","scale":4,"rotate":{"axis":[1,0,0],"deg":90},
             "children":[{"type":"superelliptic_cylinder","radii":[4,4,4],"n":2,"half_length":12}]}]}})"},
    {"bt_hyperellipsoid_box",
     R"({"convention":"zero","bounds":[[-12,-12,-12],[12,12,12]],"field":{"type":"bt_intersection","base":"hyperellipsoid","r":[2,2,2],"p":[3,3,3],
          "children":[
            {"type":"offset","scale":8,"children":[{"type":"parallel_planes","normal":[1,0,0],"a":8}]},
            {"type":"offset","scale":8,"children":[{"type":"parallel_planes","normal":[0,1,0],"a":8}]},
            {"type":"offset","scale":8,"children":[{"type":"parallel_planes","normal":[0,0,1],"a":8}]}]}})"},
    // [003] Fig. 9's wheel (scenes/fig003_9_wheel.json, m1 = 0.3) scaled by 6: bulge elimination,
    // whose box bounds come from the spokes' Hessian bounds.
    {"bt_bulge_wheel",
     R"({"convention":"zero","bounds":[[-16.5,-16.5,-4.2],[16.5,16.5,4.2]],"field":{"type":"bt_union","base":"hyperellipsoid","r":[1,1],"p":[2,2],
          "children":[
            {"type":"bt_union","base":"hyperellipsoid","r":[0.8,0.8],"p":[2,2],"m":[0.3,1],"bulge_elimination":{"omega":0.05},
             "children":[
               {"type":"offset","children":[{"type":"segment","p0":[-11.1,0,0],"p1":[11.1,0,0],"radius":0.96}]},
               {"type":"offset","children":[{"type":"segment","p0":[0,-11.1,0],"p1":[0,11.1,0],"radius":0.96}]}]},
            {"type":"offset","children":[{"type":"torus","major_radius":12,"radii":[1.5,1.5]}]}]}})"},
};

Scene load(const Model& m) {
  return parse_scene(std::string(R"({"camera":{"eye":[60,-80,50],"target":[0,0,0]},"objects":[)") +
                         m.object + "]}",
                     m.name);
}

std::vector<Vec3> points_in(const Box& b, int n) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> pts(n);
  for (auto& p : pts)
    p = {b.lo.x + u(rng) * b.extent().x, b.lo.y + u(rng) * b.extent().y,
         b.lo.z + u(rng) * b.extent().z};
  return pts;
}

void BM_ValueAndGradient(benchmark::State& state, const Model* m) {
  const Scene s = load(*m);
  const auto pts = points_in(s.objects[0].bounds, 4096);
  size_t i = 0;
  for (auto _ : state) {
    Vec3 g;
    benchmark::DoNotOptimize(s.objects[0].field->eval(pts[i++ & 4095], &g));
    benchmark::DoNotOptimize(g);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_IntervalAndLipschitz(benchmark::State& state, const Model* m) {
  const Scene s = load(*m);
  const auto pts = points_in(s.objects[0].bounds, 4096);
  const double r = 0.02 * s.objects[0].bounds.diagonal();
  size_t i = 0;
  for (auto _ : state) {
    const Box b = Box::around(pts[i++ & 4095], r);
    benchmark::DoNotOptimize(s.objects[0].field->interval(b));
    benchmark::DoNotOptimize(s.objects[0].field->lipschitz(b));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_FirstHit(benchmark::State& state, const Model* m, LipschitzMode mode) {
  const Scene s = load(*m);
  const ObjectTracer tr(s.objects[0], mode);
  const Box& b = s.objects[0].bounds;
  const auto targets = points_in(Box(b.center() - b.extent() * 0.2, b.center() + b.extent() * 0.2), 1024);
  const Vec3 eye{60, -80, 50};
  size_t i = 0;
  long long steps_total = 0;
  for (auto _ : state) {
    int steps = 0;
    const Vec3 t = targets[i++ & 1023];
    benchmark::DoNotOptimize(tr.first_hit({eye, normalize(t - eye)}, 0, 1e9, steps));
    steps_total += steps;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["evals/ray"] = benchmark::Counter(static_cast<double>(steps_total) /
                                                   std::max<int64_t>(1, state.iterations()));
}

void register_all() {
  for (const Model& m : kModels) {
    benchmark::RegisterBenchmark((std::string("eval/") + m.name).c_str(), BM_ValueAndGradient, &m);
    benchmark::RegisterBenchmark((std::string("interval/") + m.name).c_str(),
                                 BM_IntervalAndLipschitz, &m);
    benchmark::RegisterBenchmark((std::string("first_hit_local/") + m.name).c_str(), BM_FirstHit,
                                 &m, LipschitzMode::Local);
    benchmark::RegisterBenchmark((std::string("first_hit_global/") + m.name).c_str(), BM_FirstHit,
                                 &m, LipschitzMode::Global);
  }
}

}  // namespace
}  // namespace softtrace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  softtrace::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}

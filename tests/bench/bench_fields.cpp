// Google Benchmark microbenchmarks of field evaluation and of the tracer's first-hit search.
// Not a test: run build/tests/softtrace_bench (see README "Benchmarks").
#include <benchmark/benchmark.h>

#include <random>

#include "eval/eval.h"
#include "model/program_builder.h"
#include "scene/traced_objects.h"
#include "trace/tracer.h"

namespace softtrace {
namespace {

struct Model {
  const char* name;
  const char* object;  // one scene object
};

const Model kModels[] = {
    {"fig000_12b_soft_blend",
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

// The model tree's own methods: the baseline the compiled program is measured against.
void BM_ModelValueAndGradient(benchmark::State& state, const Model* m) {
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

// The box question: interval and Lipschitz bound together, as one bounds() call (node.h).
void BM_ModelIntervalAndLipschitz(benchmark::State& state, const Model* m) {
  const Scene s = load(*m);
  const auto pts = points_in(s.objects[0].bounds, 4096);
  const double r = 0.02 * s.objects[0].bounds.diagonal();
  size_t i = 0;
  for (auto _ : state) {
    const Box b = Box::around(pts[i++ & 4095], r);
    benchmark::DoNotOptimize(s.objects[0].field->bounds(b));
  }
  state.SetItemsProcessed(state.iterations());
}

// One point's value on the compiled program, pruned to the point where that pays (evaluate()).
void BM_PointValue(benchmark::State& state, const Model* m) {
  const Scene s = load(*m);
  const Program prog = compile(*s.objects[0].field);
  Workspace ws;
  ws.fit(prog);
  const auto pts = points_in(s.objects[0].bounds, 4096);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(evaluate(prog, pts[i++ & 4095], nullptr, ws));
  state.SetItemsProcessed(state.iterations());
}

// Eight points as one batch (structure of arrays) against eight single-point calls: the same
// points, items = points.
void BM_Batch8(benchmark::State& state, const Model* m, bool batched) {
  const Scene s = load(*m);
  const Program prog = compile(*s.objects[0].field);
  Workspace ws;
  ws.fit(prog);
  const auto pts = points_in(s.objects[0].bounds, 4096);
  double x[4096], y[4096], z[4096], f[8];
  for (int i = 0; i < 4096; ++i) x[i] = pts[i].x, y[i] = pts[i].y, z[i] = pts[i].z;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = (i += 8) & 4095;
    if (batched) {
      values(prog, x + k, y + k, z + k, 8, f, ws);
    } else {
      for (int l = 0; l < 8; ++l) f[l] = value(prog, pts[k + l], ws);
    }
    benchmark::DoNotOptimize(f);
  }
  state.SetItemsProcessed(8 * state.iterations());
}

// The fused box pass: interval, Lipschitz bound and pruned program in one walk.
void BM_BoxPass(benchmark::State& state, const Model* m) {
  const Scene s = load(*m);
  const Program prog = compile(*s.objects[0].field);
  Workspace ws;
  ws.fit(prog);
  const auto pts = points_in(s.objects[0].bounds, 4096);
  const double r = 0.02 * s.objects[0].bounds.diagonal();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(bounds(prog, Box::around(pts[i++ & 4095], r), ws));
  state.SetItemsProcessed(state.iterations());
}

// N murakami blobs (tools/blob_scene.py's model: centres in [-20, 20]^3, radius 6 (1000/N)^(1/3)):
// pruning a box the size of one blob's support costs O(log N + k).
std::string blobs_object(int n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-20, 20);
  const double r = 6 * std::cbrt(1000.0 / n);
  std::string s = R"({"field":{"type":"soft_blend","children":[)";
  for (int i = 0; i < n; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    s += (i ? "," : "") + std::string(R"({"type":"soft_object","potential":{"type":"murakami"},)") +
         R"("distance":{"type":"lp_metric","radii":[)" + std::to_string(r) + "," +
         std::to_string(r) + "," + std::to_string(r) + R"(],"n":2},"translate":[)" +
         std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z) + "]}";
  }
  return s + "]}}";
}

void BM_BlobBoxPass(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string object = blobs_object(n);
  const Model m{"blobs", object.c_str()};
  const Scene s = load(m);
  const Program prog = compile(*s.objects[0].field);
  Workspace ws;
  ws.fit(prog);
  const double r = 6 * std::cbrt(1000.0 / n);
  const auto pts = points_in(Box({-20, -20, -20}, {20, 20, 20}), 4096);
  size_t i = 0;
  long long kept = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bounds(prog, Box::around(pts[i++ & 4095], r), ws));
    kept += ws.view.code.back().n;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["children"] =
      benchmark::Counter(static_cast<double>(kept) / std::max<int64_t>(1, state.iterations()));
  // The time per child kept: O(log N + k) shows as a cost per child that hardly grows with N.
  state.counters["s/child"] = benchmark::Counter(
      static_cast<double>(kept), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_FirstHit(benchmark::State& state, const Model* m, LipschitzMode mode) {
  const Scene s = load(*m);
  const ObjectTracer tr(trace_target(s.objects[0]), mode);
  const Box& b = s.objects[0].bounds;
  const auto targets =
      points_in(Box(b.center() - b.extent() * 0.2, b.center() + b.extent() * 0.2), 1024);
  const Vec3 eye{60, -80, 50};
  size_t i = 0;
  long long steps_total = 0;
  for (auto _ : state) {
    TraceCounters work;
    const Vec3 t = targets[i++ & 1023];
    benchmark::DoNotOptimize(tr.first_hit({eye, normalize(t - eye)}, 0, 1e9, work));
    steps_total += work.evaluations();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["evals/ray"] = benchmark::Counter(static_cast<double>(steps_total) /
                                                   std::max<int64_t>(1, state.iterations()));
}

void register_all() {
  benchmark::RegisterBenchmark("blob_box_pass", BM_BlobBoxPass)->Arg(100)->Arg(1000)->Arg(10000);
  for (const Model& m : kModels) {
    benchmark::RegisterBenchmark((std::string("model_eval/") + m.name).c_str(),
                                 BM_ModelValueAndGradient, &m);
    benchmark::RegisterBenchmark((std::string("model_interval_lipschitz/") + m.name).c_str(),
                                 BM_ModelIntervalAndLipschitz, &m);
    benchmark::RegisterBenchmark((std::string("point_value/") + m.name).c_str(), BM_PointValue, &m);
    benchmark::RegisterBenchmark((std::string("batch8/") + m.name).c_str(), BM_Batch8, &m, true);
    benchmark::RegisterBenchmark((std::string("single_x8/") + m.name).c_str(), BM_Batch8, &m,
                                 false);
    benchmark::RegisterBenchmark((std::string("box_pass/") + m.name).c_str(), BM_BoxPass, &m);
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

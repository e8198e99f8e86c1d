// Evaluation allocates nothing once a thread's Workspace is fitted (issue 10): for every sweep
// case (every node kind) and every object of every scene in scenes/, the compiled program's
// batch values (on the whole program and on a pruned view), gradient, box bounds, pruning and
// point evaluation are run many times while global operator new counts its calls.
// Replacing operator new/delete is global to the executable, hence an executable of its own.
// The replacements call malloc/free, which AddressSanitizer intercepts, so they coexist with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "eval/eval.h"
#include "model/node.h"
#include "model/program_builder.h"
#include "scene/scene.h"
#include "scene_files.h"
#include "sweep.h"

namespace {

std::atomic<long> g_allocations{0};
volatile double g_sink;  // keeps the evaluations' results observable

void* counted(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* counted_or_throw(std::size_t n) {
  if (void* p = counted(n)) return p;
  throw std::bad_alloc();
}
void* counted_aligned(std::size_t n, std::align_val_t al) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(al);
  return std::aligned_alloc(a, (std::max<std::size_t>(n, 1) + a - 1) / a * a);
}
void* counted_aligned_or_throw(std::size_t n, std::align_val_t al) {
  if (void* p = counted_aligned(n, al)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t n) {
  return counted_or_throw(n);
}
void* operator new[](std::size_t n) {
  return counted_or_throw(n);
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return counted(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return counted(n);
}
void* operator new(std::size_t n, std::align_val_t a) {
  return counted_aligned_or_throw(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return counted_aligned_or_throw(n, a);
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_aligned(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_aligned(n, a);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}

namespace softtrace {
namespace {

constexpr int kPoints = 128;  // a multiple of kLanes
constexpr int kLanes = 8;     // the values batch
constexpr int kRounds = 4;    // counted repetitions after the warm-up
const double kBoxScales[] = {1.0, 0.25, 1.0 / 16, 1.0 / 256};
constexpr int kBoxesPerScale = 8;

struct Inputs {
  std::vector<Vec3> points;
  std::vector<double> x, y, z;
  std::vector<Box> boxes;
};

Inputs inputs_in(const Box& domain) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(0, 1);
  const auto point = [&](const Box& b) {
    return Vec3{b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
                b.lo.z + u(rng) * (b.hi.z - b.lo.z)};
  };
  Inputs in;
  for (int i = 0; i < kPoints; ++i) {
    in.points.push_back(point(domain));
    in.x.push_back(in.points.back().x);
    in.y.push_back(in.points.back().y);
    in.z.push_back(in.points.back().z);
  }
  for (double s : kBoxScales)
    for (int i = 0; i < kBoxesPerScale; ++i) {
      const Vec3 c = point(domain), h = domain.extent() * (0.5 * s);
      in.boxes.push_back({c - h, c + h});
    }
  return in;
}

// Allocations counted in each evaluator.
struct Counts {
  long values = 0, view_values = 0, gradient = 0, bounds = 0, prune = 0, evaluate = 0;
};

long allocations() {
  return g_allocations.load(std::memory_order_relaxed);
}

// One pass of every evaluator over the inputs; when `c` is non-null, the allocations of each go
// there. `sink` keeps the results alive.
void run(const Program& p, const Inputs& in, Workspace& ws, Counts* c, double* sink) {
  double f[kLanes];
  long at = allocations();
  const auto take = [&](long Counts::*evaluator) {
    const long now = allocations();
    if (c) c->*evaluator += now - at;
    at = now;
  };
  for (int i = 0; i < kPoints; i += kLanes) {
    values(p, &in.x[i], &in.y[i], &in.z[i], kLanes, f, ws);
    *sink += f[0];
  }
  take(&Counts::values);
  for (const Vec3& q : in.points) {
    Vec3 g;
    *sink += gradient(p, q, &g, ws) + g.x;
  }
  take(&Counts::gradient);
  for (const Box& b : in.boxes) {
    const BoxBounds r = bounds(p, b, ws);
    *sink += r.value.lo + r.lipschitz;
    take(&Counts::bounds);
    // The tracer's use of the view: points of the box evaluated on the program pruned to it.
    const Vec3 mid = b.center();
    const double xs[2] = {b.lo.x, mid.x}, ys[2] = {b.lo.y, mid.y}, zs[2] = {b.lo.z, mid.z};
    values(ws.view, xs, ys, zs, 2, f, ws);
    Vec3 g;
    *sink += f[1] + gradient(ws.view, mid, &g, ws);
    take(&Counts::view_values);
    prune(p, b, ws);
    *sink += static_cast<double>(ws.view.code.size());
    take(&Counts::prune);
  }
  for (const Vec3& q : in.points) {
    Vec3 g;
    *sink += evaluate(p, q, nullptr, ws) + evaluate(p, q, &g, ws);
  }
  take(&Counts::evaluate);
}

void expect_no_allocation(const FieldNode& field, const Box& domain) {
  ASSERT_TRUE(domain.bounded());
  const Program p = compile(field);
  const Inputs in = inputs_in(domain);
  Workspace ws;
  ws.fit(p);
  double sink = 0;
  run(p, in, ws, nullptr, &sink);  // warm-up: first-use statics
  Counts c;
  for (int r = 0; r < kRounds; ++r) run(p, in, ws, &c, &sink);
  EXPECT_EQ(c.values, 0) << "values";
  EXPECT_EQ(c.gradient, 0) << "gradient";
  EXPECT_EQ(c.bounds, 0) << "bounds";
  EXPECT_EQ(c.view_values, 0) << "values and gradient on the pruned view";
  EXPECT_EQ(c.prune, 0) << "prune";
  EXPECT_EQ(c.evaluate, 0) << "evaluate";
  g_sink = sink;
}

// Every sweep case, listed by the family files compiled with SOFTTRACE_SWEEP_LIST_ONLY.
}  // namespace
namespace test {
void PrintTo(const ListedCase& c, std::ostream* os) {
  *os << c.family << "/" << c.c->name;
}
}  // namespace test
namespace {

class SweepNoAlloc : public testing::TestWithParam<test::ListedCase> {};

TEST_P(SweepNoAlloc, EvaluatorsDoNotAllocate) {
  const test::SweepCase& c = *GetParam().c;
  const NodePtr n = test::build_from_json(c.json, c.convention);
  expect_no_allocation(*n, c.domain);
}

INSTANTIATE_TEST_SUITE_P(Sweep, SweepNoAlloc, testing::ValuesIn(test::sweep_cases()),
                         [](const testing::TestParamInfo<test::ListedCase>& i) {
                           return i.param.family + "_" + i.param.c->name;
                         });

std::vector<std::string> scene_names() {
  std::vector<std::string> names;
  for (const auto& f : test::scene_files()) names.push_back(f.stem().string());
  return names;
}

class SceneNoAlloc : public testing::TestWithParam<std::string> {};

TEST_P(SceneNoAlloc, EvaluatorsDoNotAllocate) {
  const Scene s = load_scene(SOFTTRACE_SOURCE_DIR "/scenes/" + GetParam() + ".json");
  ASSERT_FALSE(s.objects.empty());
  int fields = 0;
  // A plain primitive has no evaluator; a CSG's fields are among its operands.
  const std::function<void(const SceneObject&)> visit = [&](const SceneObject& o) {
    if (o.csg)
      for (const SceneObject& operand : o.csg->operands) visit(operand);
    if (!o.field) return;
    SCOPED_TRACE(o.name);
    expect_no_allocation(*o.field, o.bounds);
    ++fields;
  };
  for (const SceneObject& o : s.objects) visit(o);
  EXPECT_GT(fields, 0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneNoAlloc, testing::ValuesIn(scene_names()),
                         [](const testing::TestParamInfo<std::string>& i) { return i.param; });

// Nodes with one term per child keep their per-call arrays on the stack up to 16 children
// (scratch.h); beyond that they fall back to the heap, which this limit documents.
std::string soft_ball(int i) {
  return R"({"type":"soft_object","translate":[)" + std::to_string(0.3 * i) +
         R"(,0,0],"distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})";
}
std::string lp_ball(int i) {
  return R"({"type":"lp_metric","translate":[)" + std::to_string(0.3 * i) +
         R"(,0,0],"radii":[1,1,1],"n":2})";
}
std::string children(int k, std::string (*child)(int)) {
  std::string s;
  for (int i = 0; i < k; ++i) s += (i ? "," : "") + child(i);
  return "[" + s + "]";
}

TEST(NoAlloc, SixteenChildrenStayOnTheStack) {
  const Box domain({-1.5, -1.5, -1.5}, {6, 1.5, 1.5});
  const std::string soft = children(16, soft_ball), dist = children(16, lp_ball);
  const std::string normals = [] {
    std::string s;
    for (int i = 0; i < 16; ++i) {
      const double a = 0.4 * i;
      s += (i ? ",[" : "[") + std::to_string(std::cos(a)) + "," + std::to_string(std::sin(a)) +
           ",0.5]";
    }
    return "[" + s + "]";
  }();
  const std::pair<const char*, std::string> cases[] = {
      {"ricci_union", R"({"type":"ricci_union","n":3,"children":)" + soft + "}"},
      {"ricci_intersection", R"({"type":"ricci_intersection","n":3,"children":)" + soft + "}"},
      {"perlin_union", R"({"type":"perlin_union","children":)" + soft + "}"},
      {"super_ellipsoidal_union",
       R"({"type":"super_ellipsoidal_union","n":4,"children":)" + dist + "}"},
      {"super_ellipsoidal_intersection",
       R"({"type":"super_ellipsoidal_intersection","n":4,"children":)" + dist + "}"},
      {"generalized_distance",
       R"({"type":"generalized_distance","a":1,"n":4,"normals":)" + normals + "}"},
  };
  for (const auto& [name, json] : cases) {
    SCOPED_TRACE(name);
    expect_no_allocation(*test::build_from_json(json), domain);
  }
}

}  // namespace
}  // namespace softtrace

// softtrace-core carries its own C++ runtime and libgcc (-static-libstdc++ -static-libgcc) and
// opens Embree on demand (cli/embree_on_demand.cpp); libembree3 brings the shared runtime beside
// them. An exception thrown in one of our Embree callbacks would be unwound by the program's
// libgcc through libembree3's frames, whose handlers are the shared runtime's: the process
// aborted (seen here: SIGABRT inside libgcc_s, called from the shared runtime's personality
// routine, on the first such exception). So the callbacks catch their own (embree_scene.cpp's
// guarded) and the call's check throws them as one line. This executable is linked as
// softtrace-core is, and makes a CSG's callback fail to allocate: the renderer_tests run on the
// shared runtime alone, where the crossing does not exist.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <link.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <thread>

#include "render/frame.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"

namespace {

// The next `t_failures` calls of operator new on this thread fail. The first allocation inside
// one EmbreeScene::intersect of a CSG is its callback's (CsgTracer::spans' list), so it is the
// callback that throws. Only this program's operator new: libembree3 and the shared runtime keep
// their own.
thread_local int t_failures = 0;

}  // namespace

void* operator new(std::size_t bytes) {
  if (t_failures > 0) {
    --t_failures;
    throw std::bad_alloc();
  }
  if (void* p = std::malloc(bytes ? bytes : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace softtrace {
namespace {

// Whether `name` (part of a file name) is among the objects mapped in the process now.
bool mapped(const char* name) {
  struct Search {
    const char* name;
    bool found;
  } search{name, false};
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        auto* s = static_cast<Search*>(data);
        if (info->dlpi_name && std::string(info->dlpi_name).find(s->name) != std::string::npos)
          s->found = true;
        return 0;
      },
      &search);
  return search.found;
}

// Whether the program's own runtime answers for std::terminate (not libstdc++.so).
bool own_runtime() {
  Dl_info info{};
  return !(dladdr(reinterpret_cast<void*>(&std::terminate), &info) && info.dli_fname &&
           std::string(info.dli_fname).find("libstdc++.so") != std::string::npos);
}

TEST(CoreRuntime, TheProgramCarriesItsOwnRuntime) {
  EXPECT_TRUE(own_runtime());
  EXPECT_FALSE(mapped("libstdc++.so")) << "linked unlike softtrace-core";
}

// A CSG (a sphere less a box), which Embree traces through csg_intersect_callback.
const char* const kCsg = R"({"camera": {"eye": [0, -10, 0], "target": [0, 0, 0]},
  "objects": [{"csg": "difference", "operands": [
    {"shape": {"type": "sphere", "radius": 2}},
    {"shape": {"type": "box", "corner1": [0, 0, -3], "corner2": [3, 3, 3]}}]}]})";

// What a call throws on a thread of its own whose first allocation fails: "" for nothing, and
// "" too unless that allocation was made.
template <class Call>
std::string failing(const Call& call) {
  std::string what = "";
  std::thread([&] {
    t_failures = 1;
    try {
      call();
    } catch (const EmbreeError& e) {
      what = e.what();
    } catch (const std::exception& e) {
      what = std::string("not an EmbreeError: ") + e.what();
    }
    if (t_failures != 0) what = "";
  }).join();
  return what;
}

TEST(CoreRuntime, ACallbacksAllocationFailureIsOneLineNotAnAbort) {
  if (!own_runtime()) GTEST_SKIP() << "this build links the shared C++ runtime: no crossing";
  const Scene scene = parse_scene(kCsg, "csg.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  ASSERT_TRUE(mapped("libembree3")) << "the CSG is not traced through Embree";
  ASSERT_TRUE(mapped("libstdc++.so")) << "Embree is open, but no shared runtime beside ours";
  const Ray ray{{-0.5, -10, 0.5}, {0, 1, 0}};
  // Traced normally first: the ray meets the sphere.
  EXPECT_TRUE(rt.embree.intersect(ray, 0, INFINITY).hit);
  for (int i = 0; i < 20; ++i) {  // every time, not once
    EXPECT_EQ(failing([&] { rt.embree.intersect(ray, 0, INFINITY); }),
              "Embree failed tracing a ray: out of memory")
        << i;
    TraceCounters work;
    EXPECT_EQ(failing([&] { rt.embree.occluded(ray, 0, INFINITY, work); }),
              "Embree failed tracing a shadow ray: out of memory")
        << i;
  }
  // And the scene traces on afterwards.
  EXPECT_TRUE(rt.embree.intersect(ray, 0, INFINITY).hit);
}

}  // namespace
}  // namespace softtrace

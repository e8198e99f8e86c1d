// The sweep every node kind goes through (libfive's habit: one cheap exhaustive test over all
// kinds): gradient vs central differences, Lipschitz bounds vs sampled gradients and difference
// quotients (global and over random boxes), interval enclosures vs sampled values, and region
// boxes vs sampled points. A family adds its cases with
//   SOFTTRACE_SWEEP_FAMILY(Family, kCases);
// which instantiates the sweep on them and lists them in sweep_cases(), for the tests that put
// every kind through something else (test_no_alloc.cpp). Such an executable compiles the family
// files with SOFTTRACE_SWEEP_LIST_ONLY defined: it gets the list without the sweep's tests.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "describe/building.h"
#include "math/box.h"
#include "model/node.h"

namespace softtrace::test {

struct SweepCase {
  std::string name;  // test-name safe: letters, digits, underscores
  std::string json;  // the node, as in a scene ("//" comments allowed)
  Box domain;        // where points and boxes are drawn
  Convention convention = Convention::Soft;
  // Regions checked: {f >= level} (Above) or {f <= level} (Below) must lie in region().
  // Use NaN to skip (fields with no finite region).
  double region_level = 1e-300;
  Side region_side = Side::Above;
};

// The domains most families draw from: the unit kinds fill kUnit, blends and far children kWide.
inline const Box kUnit({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5});
inline const Box kWide({-3, -3, -3}, {3, 3, 3});

inline void PrintTo(const SweepCase& c, std::ostream* os) {
  *os << c.name;
}

inline std::string SweepCaseName(const testing::TestParamInfo<SweepCase>& info) {
  return info.param.name;
}

class NodeSweep : public testing::TestWithParam<SweepCase> {};

// A uniform point in b, and a random box in `domain` of e^-5 to e^-1 of its size: where the
// sweeps sample.
inline Vec3 uniform_in(std::mt19937_64& rng, const Box& b) {
  std::uniform_real_distribution<double> u(0, 1);
  return {b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
          b.lo.z + u(rng) * (b.hi.z - b.lo.z)};
}
inline Box random_box(std::mt19937_64& rng, const Box& domain) {
  const double scale = std::exp(std::uniform_real_distribution<double>(-5, -1)(rng));
  const Vec3 c = uniform_in(rng, domain), e = domain.extent() * (0.5 * scale);
  return {c - e, c + e};
}

// Builds a node from JSON text; the text is parsed with comments allowed.
NodePtr build_from_json(const std::string& json, Convention convention = Convention::Soft);

// The message building `json` fails with, or "" when it builds.
inline std::string build_error(const std::string& json, Convention c = Convention::Soft) {
  try {
    build_from_json(json, c);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// Calls fn on `count` points drawn uniformly from [-r, r]^3, the same ones for the same seed.
template <class F>
void for_random_points(int count, double r, uint64_t seed, F&& fn) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-r, r);
  for (int i = 0; i < count; ++i) fn(Vec3{u(rng), u(rng), u(rng)});
}

struct ListedCase {
  std::string family;
  const SweepCase* c;
};

// Every family's cases in this executable (filled during static initialisation).
inline std::vector<ListedCase>& sweep_cases() {
  static std::vector<ListedCase> cases;
  return cases;
}

inline bool list_sweep_cases(const char* family, const SweepCase* first, const SweepCase* last) {
  for (; first != last; ++first) sweep_cases().push_back({family, first});
  return true;
}

#define SOFTTRACE_SWEEP_LIST(family, cases)     \
  [[maybe_unused]] const bool family##_listed = \
      ::softtrace::test::list_sweep_cases(#family, std::begin(cases), std::end(cases))
#ifdef SOFTTRACE_SWEEP_LIST_ONLY
#define SOFTTRACE_SWEEP_FAMILY(family, cases) SOFTTRACE_SWEEP_LIST(family, cases)
#else
#define SOFTTRACE_SWEEP_FAMILY(family, cases)                                           \
  INSTANTIATE_TEST_SUITE_P(family, NodeSweep, testing::ValuesIn(cases), SweepCaseName); \
  SOFTTRACE_SWEEP_LIST(family, cases)
#endif

}  // namespace softtrace::test

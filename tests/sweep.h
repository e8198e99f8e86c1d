// The sweep every node kind goes through (libfive's habit: one cheap exhaustive test over all
// kinds): gradient vs central differences, Lipschitz bounds vs sampled gradients and difference
// quotients (global and over random boxes), interval enclosures vs sampled values, and region
// boxes vs sampled points. A family adds its cases with
//   SOFTTRACE_SWEEP(Family, kCases);
// which also records them for the test that every kind of kinds.h has a case (test_kinds.cpp).
#pragma once

#include <gtest/gtest.h>

#include <iterator>
#include <string>
#include <vector>

#include "registry.h"

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

inline void PrintTo(const SweepCase& c, std::ostream* os) {
  *os << c.name;
}

inline std::string SweepCaseName(const testing::TestParamInfo<SweepCase>& info) {
  return info.param.name;
}

class NodeSweep : public testing::TestWithParam<SweepCase> {};

// Every case of every family, as registered by SOFTTRACE_SWEEP.
std::vector<const SweepCase*>& sweep_cases();
inline int register_sweep_cases(const SweepCase* begin, const SweepCase* end) {
  for (const SweepCase* c = begin; c != end; ++c) sweep_cases().push_back(c);
  return 0;
}
#define SOFTTRACE_SWEEP(Family, cases)                                                  \
  INSTANTIATE_TEST_SUITE_P(Family, NodeSweep, testing::ValuesIn(cases), SweepCaseName); \
  [[maybe_unused]] const int Family##_registered =                                      \
      register_sweep_cases(std::begin(cases), std::end(cases))

// Builds a node from JSON text; the text is parsed with comments allowed.
NodePtr build_from_json(const std::string& json, Convention convention = Convention::Soft);

}  // namespace softtrace::test

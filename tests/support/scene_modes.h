// Tests over a table of scene cases, each traced with both Lipschitz modes: the parameter
// generator and the test names ("<case>_local", "<case>_global").
#pragma once

#include <gtest/gtest.h>

#include <iterator>
#include <string>
#include <tuple>

#include "trace/tracer.h"

namespace softtrace {

using SceneMode = std::tuple<int, LipschitzMode>;

template <class Case, size_t N>
auto scene_modes(const Case (&)[N]) {
  return testing::Combine(testing::Range(0, int(N)),
                          testing::Values(LipschitzMode::Local, LipschitzMode::Global));
}

template <class Case, size_t N>
std::string scene_mode_name(const Case (&cases)[N], const testing::TestParamInfo<SceneMode>& i) {
  return std::string(cases[std::get<0>(i.param)].name) +
         (std::get<1>(i.param) == LipschitzMode::Local ? "_local" : "_global");
}

}  // namespace softtrace

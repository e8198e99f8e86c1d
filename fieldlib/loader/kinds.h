// The one list of kinds: every field node, potential and radius transform a scene may name, with
// its family, its parameters (type, range, default) and the paper it comes from. The loader checks
// parameters against it before a kind's `create` runs, `softtrace nodes` prints it, the fuzzer
// dictionary is generated from it and docs/scene-format.md is tested against it. Adding a kind is
// one entry here plus its `create`, kernels and tests.
#pragma once

#include <string>
#include <vector>

#include "describe/kind_info.h"

namespace softtrace {

// `softtrace nodes`: every kind with its family, summary and parameter lines.
std::string describe_kinds();
// A libFuzzer dictionary: every kind name, parameter name and choice as a JSON string token.
std::string fuzz_dictionary();

}  // namespace softtrace

// The subcommands of the `softtrace` command line (SCENE.md "Command line"). Each returns the
// process exit status: 0 success, 1 a diff over its thresholds, 2 bad usage or bad input.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "tracer.h"

namespace softtrace {

struct RenderArgs {
  std::string scene;
  std::vector<std::string> outputs;
  int width = 0, height = 0, spp = 0, threads = 0;  // 0: the scene's value / all cores
  std::string aovs;
  bool quiet = false;
  LipschitzMode lipschitz = LipschitzMode::Local;
};
int run_render(const RenderArgs& a);

struct EvalArgs {
  std::string scene, object, points;
};
int run_eval(const EvalArgs& a);

// Thresholds are float, as idiff's, so a percentage such as 0.3 counts exactly as it does there.
struct DiffArgs {
  std::string a, b, out;
  float fail = 1e-6f, failpercent = 0, warn = 1e-6f, warnpercent = 0;
  float hardfail = std::numeric_limits<float>::infinity();
};
int run_diff(const DiffArgs& a);

struct BenchArgs {
  std::string scene;
  int width = 0, height = 0, threads = 0, repeat = 3;
  bool json = false;
  LipschitzMode lipschitz = LipschitzMode::Local;
};
int run_bench(const BenchArgs& a);

// `softtrace nodes`: every node, potential and radius transform with its parameters (kinds.h);
// with `dict`, the libFuzzer dictionary of their names instead.
int run_nodes(bool dict);

// "softtrace: <message>" on stderr, one line.
void report_error(const std::string& message);

}  // namespace softtrace

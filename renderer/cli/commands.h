// The subcommands of the `softtrace` command line (docs/scene-format.md "Command line"). Each
// returns the process exit status: 0 success, 2 bad usage or bad input; `diff` has idiff's codes (0
// pass, 1 warning, 2 failure, 4 a file it cannot read or write).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "trace/tracer.h"

namespace softtrace {

// --eye, --target (each "X,Y,Z", checked by point_xyz) and --fov over the scene's camera, as
// `render` and `bench` take them (cmd_common.h apply_camera_options).
struct CameraArgs {
  std::optional<std::string> eye, target;
  std::optional<double> fov;
};

struct RenderArgs {
  std::string scene;
  std::vector<std::string> outputs;
  int width = 0, height = 0, spp = 0, threads = 0;  // 0: the scene's value / all cores
  double scale = 0;                                 // 0: none (cmd_common.h apply_image_size)
  std::string aovs;
  bool quiet = false, progress = false;  // progress: the bar even when stderr is no terminal
  bool flatten = false, half = false, png_alpha = false;  // OutputOptions (film.h)
  LipschitzMode lipschitz = LipschitzMode::Local;
  // At most one: the part of the frame to render. Given but empty is refused, not the whole frame.
  std::optional<std::string> crop, pixel_bounds, tile;
  int frame = -1;                   // -1: the scene's camera, no animation frame
  CameraArgs view;                  // after the frame's camera is set
  std::optional<double> antialias;  // the adaptive anti-aliasing threshold, over the scene's
};
int run_render(const RenderArgs& a);
// What SIGINT/SIGTERM do to `render` (signals.h), by phase: see cmd_render.cpp.
void on_render_interrupt(int sig);

struct MergeArgs {
  std::vector<std::string> tiles;
  std::string output;
  bool quiet = false;
};
int run_merge(const MergeArgs& a);

struct EvalArgs {
  std::string scene, object, points;
};
int run_eval(const EvalArgs& a);

// `softtrace mesh` (cli/cmd_mesh.cpp): voxel > 0 wins over cells; threads 0: all cores.
struct MeshArgs {
  std::string scene, output, object, bounds;
  double voxel = 0;
  int cells = 128, threads = 0;
  bool quiet = false, progress = false;
};
int run_mesh(const MeshArgs& a);

// Thresholds are float, as idiff's, so a percentage such as 0.3 counts exactly as it does there.
struct DiffArgs {
  std::string a, b, out, channels;  // channels: "R,G,B" compares only those (default: shared)
  float fail = 1e-6f, failpercent = 0, failrelative = 0, warn = 1e-6f, warnpercent = 0,
        warnrelative = 0, scale = 1;
  float hardfail = std::numeric_limits<float>::infinity();
  float hardwarn = std::numeric_limits<float>::infinity();
  long long allowfailures = 0;
  bool quiet = false, abs = false, out_only_if_different = false;
};
int run_diff(const DiffArgs& a);

// idiff's single-dash options (-fail, -failpercent, -o, -abs, ...) as the double-dash ones the
// command line parser knows; other arguments unchanged. For `softtrace diff` only.
std::vector<std::string> idiff_style_arguments(const std::vector<std::string>& args);

struct BenchArgs {
  std::string scene;
  int width = 0, height = 0, threads = 0, repeat = 3;
  double scale = 0;
  bool json = false, quiet = false, progress = false;
  LipschitzMode lipschitz = LipschitzMode::Local;
  CameraArgs view;
};
int run_bench(const BenchArgs& a);

// `softtrace nodes`: every node, potential and radius transform with its parameters (kinds.h);
// with `dict`, the libFuzzer dictionary of their names instead.
int run_nodes(bool dict);

// "softtrace: <message>" on stderr, one line.
void report_error(const std::string& message);

// The whole command line: parses argv, runs the command, returns the exit status
// (command_line.cpp).
int run_command_line(int argc, char** argv);

}  // namespace softtrace

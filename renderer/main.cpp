// softtrace: render, evaluate, compare and benchmark implicit soft-object scenes.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <map>

#include "commands.h"

using namespace softtrace;

int main(int argc, char** argv) {
  CLI::App app{
      "softtrace: a CPU ray-marching renderer for implicit soft objects and their blends.\n"
      "Scene format and node list: README.md and SCENE.md."};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Print help for every subcommand");
  const std::map<std::string, LipschitzMode> modes = {{"local", LipschitzMode::Local},
                                                      {"global", LipschitzMode::Global}};

  RenderArgs r;
  auto* render = app.add_subcommand("render", "Render a scene to EXR and/or PNG");
  render->add_option("scene", r.scene, "Scene file (JSON with comments)")->required();
  render->add_option("-o,--output", r.outputs,
                     "Output image(s), .exr or .png; repeat for several (default: <scene>.exr)");
  render->add_option("--width", r.width, "Image width (overrides the scene)")
      ->check(CLI::Range(1, 16384));
  render->add_option("--height", r.height, "Image height (overrides the scene)")
      ->check(CLI::Range(1, 16384));
  render->add_option("--spp", r.spp, "Samples per pixel (overrides the scene)")
      ->check(CLI::Range(1, 4096));
  render->add_option("--threads", r.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  render->add_option("--aov", r.aovs, "Extra EXR channels: any of depth,normal,steps");
  render
      ->add_option("--lipschitz", r.lipschitz,
                   "Sphere-tracing bound: local (per stretch) or global")
      ->transform(CLI::CheckedTransformer(modes, CLI::ignore_case));
  render->add_flag("-q,--quiet", r.quiet, "No progress bar or summary");

  EvalArgs e;
  auto* eval = app.add_subcommand(
      "eval", "Print 'value gx gy gz' (%.17g) of an object's field for 'x y z' lines");
  eval->add_option("scene", e.scene, "Scene file")->required();
  eval->add_option("--object", e.object, "Object name (default: the first object)");
  eval->add_option("--points", e.points, "File of 'x y z' lines (default: standard input)");

  DiffArgs d;
  // CLI::NonNegativeNumber would print the largest double in its message.
  const CLI::Validator threshold(
      [](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        return end != text.c_str() && *end == '\0' && v >= 0
                   ? std::string()
                   : "'" + text + "' is not a number >= 0";
      },
      "T>=0");
  auto* diff = app.add_subcommand(
      "diff", "Compare two images as OpenImageIO's idiff does; exit 0 pass, 1 fail, 2 bad input");
  diff->add_option("a", d.a, "First image (e.g. the reference)")->required();
  diff->add_option("b", d.b, "Second image")->required();
  diff->add_option("--fail", d.fail, "A pixel fails when a channel differs by more (default 1e-6)")
      ->check(threshold);
  diff->add_option("--failpercent", d.failpercent,
                   "Allow this percentage of failing pixels (default 0)")
      ->check(CLI::Range(0.0, 100.0));
  diff->add_option("--warn", d.warn, "A pixel warns when a channel differs by more (default 1e-6)")
      ->check(threshold);
  diff->add_option("--warnpercent", d.warnpercent,
                   "Allow this percentage of warning pixels (default 0)")
      ->check(CLI::Range(0.0, 100.0));
  diff->add_option("--hardfail", d.hardfail,
                   "Fail if a failing pixel differs by more than this (default inf)")
      ->check(threshold);
  diff->add_option("--out", d.out,
                   "Write |A-B| here: .exr (float, all channels) or .png (8-bit RGB)");

  BenchArgs b;
  auto* bench = app.add_subcommand("bench", "Measure primary-ray intersection throughput");
  bench->add_option("scene", b.scene, "Scene file")->required();
  bench->add_option("--width", b.width, "Image width (default: the scene's)")
      ->check(CLI::Range(1, 16384));
  bench->add_option("--height", b.height, "Image height (default: the scene's)")
      ->check(CLI::Range(1, 16384));
  bench->add_option("--threads", b.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  bench->add_option("--repeat", b.repeat, "Timed frames (default 3)")->check(CLI::Range(1, 1000));
  bench->add_option("--lipschitz", b.lipschitz, "Sphere-tracing bound: local or global")
      ->transform(CLI::CheckedTransformer(modes, CLI::ignore_case));
  bench->add_flag("--json", b.json, "Print the results as JSON");

  bool dict = false;
  auto* nodes = app.add_subcommand(
      "nodes", "List the node types, potentials and radius transforms with their parameters");
  nodes->add_flag("--dict", dict, "Print a libFuzzer dictionary of their names instead");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& ex) {
    return app.exit(ex);
  } catch (const CLI::CallForAllHelp& ex) {
    return app.exit(ex);
  } catch (const CLI::ParseError& ex) {
    report_error(ex.what() + std::string(" (see softtrace --help)"));
    return 2;
  }
  if (*render) return run_render(r);
  if (*eval) return run_eval(e);
  if (*diff) return run_diff(d);
  if (*bench) return run_bench(b);
  if (*nodes) return run_nodes(dict);
  return 2;
}

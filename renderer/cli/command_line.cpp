// softtrace's command line: render, evaluate, compare and benchmark implicit soft-object scenes.
// Both programs run it: softtrace-core (core_main.cpp) and the static softtrace (static_main.cpp).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/cli_spelling.h"
#include "cli/commands.h"
#include "cli/heap_pages.h"
#include "cli/option_checks.h"
#include "cli/signals.h"
#include "cli/standard_output.h"
#include "commit.h"
#include "film/plane_memory.h"

using namespace softtrace;

namespace {
// What --version prints (CLI11 adds the newline).
constexpr const char kVersionLine[] =
    "softtrace " SOFTTRACE_VERSION " (commit " SOFTTRACE_COMMIT ")";

// --eye, --target and --fov: `render` and `bench` move the camera alike.
void add_camera_options(CLI::App* command, CameraArgs& view) {
  command->add_option("--eye", view.eye, "Camera eye X,Y,Z (overrides the scene's)")
      ->check(point_xyz());
  command->add_option("--target", view.target, "Camera target X,Y,Z (overrides the scene's)")
      ->check(point_xyz());
  command->add_option("--fov", view.fov, "Camera's vertical field of view in degrees (overrides)")
      ->check(finite_number());
}

// --width, --height and --scale (which excludes the other two), as render and bench take them.
void add_size_options(CLI::App* command, int& width, int& height, double& scale) {
  auto* w = command
                ->add_option("--width", width,
                             "Image width; alone, the height follows the scene's aspect")
                ->check(integer_in(1, 16384));
  auto* h = command
                ->add_option("--height", height,
                             "Image height; alone, the width follows the scene's aspect")
                ->check(integer_in(1, 16384));
  command->add_option("--scale", scale, "Scale the scene's width and height by F")
      ->check(number_above_zero())
      ->excludes(w, h);
}

// The command line's parser. Setting up every command's options took 0.9 M instructions at
// each start; a run that names its command sets up only that command (each other one, as a CLI11
// App of its own, cost 30,000 instructions more: a fifth of the rest), and anything but a clean
// parse (an error, --help, --version) is parsed again by the whole parser, so that every message
// and help text is the one it gives. A command not set up is null.
struct CommandLine {
  explicit CommandLine(const std::string& only);  // only this command's options; "": all

  CLI::App app{
      "softtrace: a CPU ray-marching renderer for implicit soft objects and their blends.\n"
      "Scene format and every node: docs/scene-format.md; the maths: docs/math.md; the command "
      "line: docs/cli.md."};
  RenderArgs r;
  EvalArgs e;
  MeshArgs mesh_args;
  DiffArgs d;
  BenchArgs b;
  MergeArgs m;
  bool dict = false;
  CLI::App *render, *eval, *mesh, *diff, *bench, *merge, *nodes;

 private:
  CLI::App* command(const std::string& only, const std::string& name, const std::string& summary) {
    return only.empty() || only == name ? app.add_subcommand(name, summary) : nullptr;
  }
};

CommandLine::CommandLine(const std::string& only) {
  app.footer(
      "Exit status: 0 success; 2 bad usage or bad input; 128 + the signal when interrupted (130 "
      "SIGINT, 143 SIGTERM); diff: 0 pass, 1 warning, 2 failure, 4 an image it cannot read or "
      "write.\nInstalled, the documentation is in share/doc/softtrace/ and example scenes in "
      "share/softtrace/scenes/ under the prefix.\n");
  // A flag is on when given: "--flatten=0" or "--quiet=foo" are refused rather than read.
  app.option_defaults()->disable_flag_override();
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Print help for every subcommand");
  app.set_version_flag("--version", kVersionLine,
                       "Print the version and the commit it was built from");

  render = command(only, "render", "Render a scene to EXR and/or PNG");
  if (render) {
    render->add_option("scene", r.scene, "Scene file (JSON with comments)")->required();
    render->add_option("-o,--output", r.outputs,
                       "Output image(s), .exr or .png; repeat for several (default: <scene>.exr)");
    add_size_options(render, r.width, r.height, r.scale);
    render->add_option("--spp", r.spp, "Samples per pixel (overrides the scene)")
        ->check(integer_in(1, 4096));
    render
        ->add_option("--antialias", r.antialias,
                     "Adaptive anti-aliasing threshold, POV-Ray's +A (overrides the scene)")
        ->check(number_in(0, 1e6));
    render->add_option("--threads", r.threads, "Worker threads (default: all cores)")
        ->check(integer_in(1, 1024));
    render->add_option("--aov", r.aovs, "Extra EXR channels: any of depth,normal,steps,albedo")
        ->check(aov_list());
    render
        ->add_option("--lipschitz", r.lipschitz,
                     "Sphere-tracing bound: local (per stretch) or global")
        ->transform(lipschitz_mode());
    auto* render_quiet = render->add_flag("-q,--quiet", r.quiet, "No progress bar or summary");
    render->add_flag("--progress", r.progress, "Show the progress bar even when not on a terminal")
        ->excludes(render_quiet);
    render->add_flag("--flatten", r.flatten,
                     "EXR: RGB over the scene's background with A = 1 (default: premultiplied RGBA "
                     "over transparency)");
    render->add_flag("--half", r.half, "EXR: half-float R,G,B,A and normals (Z, steps stay float)");
    render->add_flag("--png-alpha", r.png_alpha,
                     "PNG: RGBA with straight alpha (default: RGB over the background)");
    auto* crop = render->add_option(
        "--crop", r.crop, "Render fractions X0,X1,Y0,Y1 of the image (pbrt's cropwindow)");
    auto* bounds = render->add_option("--pixel-bounds", r.pixel_bounds,
                                      "Render pixels [X0,X1) x [Y0,Y1), given as X0,X1,Y0,Y1");
    auto* tile = render->add_option("--tile", r.tile,
                                    "Render tile I of N (I/N, 0 <= I < N) of a balanced split");
    crop->excludes(bounds, tile);
    bounds->excludes(tile);
    render
        ->add_option("--frame", r.frame,
                     "Render frame F (from 0) of the scene's animation; '#'s in -o become F")
        ->check(integer_in(0, 999999));

    add_camera_options(render, r.view);
  }

  eval = command(only, "eval",
                 "Print 'value gx gy gz' (%.17g) of an object's field for 'x y z' lines");
  if (eval) {
    eval->add_option("scene", e.scene, "Scene file")->required();
    eval->add_option("--object", e.object, "Object name (default: the first object)");
    eval->add_option("--points", e.points, "File of 'x y z' lines (default: standard input)");
  }

  mesh =
      command(only, "mesh", "Write an object's surface as a triangle mesh (.obj .ply .stl .glb)");
  if (mesh) {
    mesh->add_option("scene", mesh_args.scene, "Scene file")->required();
    mesh->add_option("-o,--output", mesh_args.output, "Output mesh: .obj, .ply, .stl or .glb")
        ->required();
    mesh->add_option("--object", mesh_args.object, "Object name (default: the first object)");
    auto* voxel = mesh->add_option("--voxel", mesh_args.voxel, "Cell size in scene units")
                      ->check(number_above_zero());
    mesh->add_option("--cells", mesh_args.cells,
                     "Cells along the region's longest side (default 128)")
        ->check(integer_in(1, 65536))
        ->excludes(voxel);
    mesh->add_option(
        "--bounds", mesh_args.bounds,
        "Region X0,X1,Y0,Y1,Z0,Z1 (default: the object's bounds); the mesh is capped on it");
    mesh->add_option("--threads", mesh_args.threads, "Worker threads (default: all cores)")
        ->check(integer_in(1, 1024));
    auto* mesh_quiet = mesh->add_flag("-q,--quiet", mesh_args.quiet, "No progress bar or summary");
    mesh->add_flag("--progress", mesh_args.progress,
                   "Show the progress bar even when not on a terminal")
        ->excludes(mesh_quiet);
  }

  diff = command(
      only, "diff",
      "Compare two images as OpenImageIO's idiff does (its single-dash options work too); exit 0 "
      "pass, 1 warning, 2 failure, 4 a file it cannot read or write");
  if (diff) {
    const CLI::Validator threshold = threshold_value();
    diff->add_option("a", d.a, "First image (e.g. the reference)")->required();
    diff->add_option("b", d.b, "Second image")->required();
    diff->add_option("--fail", d.fail,
                     "A pixel fails when a channel differs by more (default 1e-6)")
        ->check(threshold);
    diff->add_option("--failpercent", d.failpercent,
                     "Allow this percentage of failing pixels (default 0)")
        ->check(number_in(0, 100));
    diff->add_option("--failrelative", d.failrelative,
                     "...and by more than this fraction of the mean magnitude (default 0)")
        ->check(threshold);
    diff->add_option("--hardfail", d.hardfail,
                     "Fail if a pixel differs by more than this (default inf)")
        ->check(threshold);
    diff->add_option("--allowfailures", d.allowfailures,
                     "Pass with up to this many failing pixels (default 0)")
        ->check(integer_at_least(0));
    diff->add_option("--warn", d.warn,
                     "A pixel warns when a channel differs by more (default 1e-6)")
        ->check(threshold);
    diff->add_option("--warnpercent", d.warnpercent,
                     "Allow this percentage of warning pixels (default 0)")
        ->check(number_in(0, 100));
    diff->add_option("--warnrelative", d.warnrelative,
                     "...and by more than this fraction of the mean magnitude (default 0)")
        ->check(threshold);
    diff->add_option("--hardwarn", d.hardwarn,
                     "Warn if a pixel differs by more than this (default inf)")
        ->check(threshold);
    diff->add_option("-o,--out", d.out,
                     "Write the difference A-B here: .exr (float) or .png (8-bit RGB)");
    diff->add_flag("--abs", d.abs, "The difference image holds |A-B|");
    diff->add_option("--scale", d.scale, "Multiply the difference image by this (default 1)")
        ->check(finite_number());
    diff->add_flag("--od", d.out_only_if_different, "Write the difference image only if nonzero");
    diff->add_option("--channels", d.channels,
                     "Compare only these channels, e.g. R,G,B (default: those both images have)");
    diff->add_flag("-q,--quiet", d.quiet, "No report; FAILURE on stderr");
    // idiff's -v (its report is always printed here) and -a (all subimages: our files have one).
    diff->add_flag("-v,-a", "Accepted for idiff scripts; no effect");
  }

  bench = command(only, "bench", "Measure primary-ray intersection throughput");
  if (bench) {
    bench->add_option("scene", b.scene, "Scene file")->required();
    add_size_options(bench, b.width, b.height, b.scale);
    bench->add_option("--threads", b.threads, "Worker threads (default: all cores)")
        ->check(integer_in(1, 1024));
    bench->add_option("--repeat", b.repeat, "Timed frames (default 3)")->check(integer_in(1, 1000));
    bench->add_option("--lipschitz", b.lipschitz, "Sphere-tracing bound: local or global")
        ->transform(lipschitz_mode());
    add_camera_options(bench, b.view);
    bench->add_flag("--json", b.json, "Print the results as JSON");
    auto* bench_quiet = bench->add_flag("-q,--quiet", b.quiet, "No progress bar");
    bench->add_flag("--progress", b.progress, "Show the progress bar even when not on a terminal")
        ->excludes(bench_quiet);
  }

  merge = command(only, "merge",
                  "Put tiles (render --tile/--crop EXRs of one frame) together into one image");
  if (merge) {
    merge->add_option("tiles", m.tiles, "Tile images (.exr)")->required();
    merge->add_option("-o,--output", m.output, "Merged image (.exr or .png)")->required();
    merge->add_flag("-q,--quiet", m.quiet, "No summary line");
  }

  nodes = command(only, "nodes",
                  "List the node types, potentials and radius transforms with their parameters");
  if (nodes) {
    nodes->add_flag("--dict", dict, "Print a libFuzzer dictionary of their names instead");
  }
}

}  // namespace

int softtrace::run_command_line(int argc, char** argv) {
  // `softtrace --version` alone prints the whole parser's line without the parser: setting up
  // every command's options and CLI11's CallForVersion exception took 1.2 M of such a run's 4.0 M
  // instructions. Like the parser's answer, it exits 0 whatever the write gave. Anything else with
  // --version in it goes to the whole parser below.
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
    std::fputs(kVersionLine, stdout);
    std::fputc('\n', stdout);
    return 0;
  }
  block_interrupts();  // before anything that takes time (softtrace blocked them even sooner)
  // Before the scene fills the heap: 12 MiB covers a 3000-component scene (7.1 MB at the load's
  // peak, its JSON document's 4.5 MB of it kept with the scene until exit, so that what the
  // compile and the tracers take comes on top).
  const HeapPages heap = heap_in_huge_pages(size_t(12) << 20);
  // In the heaps' huge pages a 320x240 frame's RGBA plane (1.2 MB) takes no 2 MiB page of its own
  // (film/plane_memory.h). Only where the heap took the advice: elsewhere a mapping of its own
  // is the one that asks for huge pages.
  if (heap.end > heap.begin) planes_from_heap_below(size_t(3) << 19);
  // `diff` takes idiff's single-dash options (-fail, -failpercent, ...) as the double-dash ones.
  std::vector<std::string> args(argv, argv + argc);
  // Help names the program as users call it, wherever it lies (the launcher execs this one as
  // softtrace-core): the man page is made from this help.
  if (!args.empty()) args[0] = "softtrace";
  if (argc > 1 && args[1] == "diff") args = idiff_style_arguments(args);
  std::vector<char*> arg_pointers;
  for (auto& arg : args) arg_pointers.push_back(arg.data());
  static const char* const kCommands[] = {"render", "eval",  "mesh", "diff",
                                          "bench",  "merge", "nodes"};
  // Help lists an option's exclusions in the order of their addresses: a request for help or
  // the version goes straight to the whole parser, laid out in memory as it always was.
  const bool asks_help = std::any_of(args.begin() + 1, args.end(), [](const std::string& a) {
    return a == "-h" || a == "--help" || a == "--help-all" || a == "--version";
  });
  std::unique_ptr<CommandLine> cli, tried;
  if (argc > 1 && !asks_help &&
      std::find(std::begin(kCommands), std::end(kCommands), args[1]) != std::end(kCommands)) {
    cli = std::make_unique<CommandLine>(args[1]);
    try {
      cli->app.parse(int(arg_pointers.size()), arg_pointers.data());
    } catch (const CLI::Error&) {
      tried = std::move(cli);  // the whole parser's answer, below (this one kept, as above)
    }
  }
  if (!cli) {
    cli = std::make_unique<CommandLine>("");
    CLI::App& app = cli->app;
    try {
      app.parse(int(arg_pointers.size()), arg_pointers.data());
    } catch (const CLI::CallForHelp& ex) {
      return app.exit(ex);
    } catch (const CLI::CallForAllHelp& ex) {
      return app.exit(ex);
    } catch (const CLI::CallForVersion& ex) {
      return app.exit(ex);
    } catch (const CLI::ParseError& ex) {
      // The arguments as parsed: diff's -failpercent is --failpercent there, not an unknown word.
      const std::string unknown = unknown_word(app, int(arg_pointers.size()), arg_pointers.data());
      report_error(unknown.empty() ? usage_error_text(ex) + " (see softtrace --help)" : unknown);
      return 2;
    }
  }
  const CommandLine& c = *cli;
  // The handler is in place before any command starts to work: a signal that came while the
  // libraries were loading is taken now.
  const auto ran = [](const CLI::App* command) { return command && command->parsed(); };
  watch_interrupts(ran(c.render) ? on_render_interrupt : exit_on_interrupt);
  if (ran(c.render)) return run_render(c.r);
  if (ran(c.eval)) return checked_standard_output(run_eval(c.e), 2);
  if (ran(c.mesh)) return run_mesh(c.mesh_args);
  if (ran(c.diff)) return checked_standard_output(run_diff(c.d), 4);  // idiff's "cannot write"
  if (ran(c.bench)) return checked_standard_output(run_bench(c.b), 2);
  if (ran(c.merge)) return run_merge(c.m);
  if (ran(c.nodes)) return checked_standard_output(run_nodes(c.dict), 2);
  return 2;
}

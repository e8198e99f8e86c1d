// The command line as users meet it: bad scenes, output safety, eval, AOVs, determinism.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>

#include "cli_util.h"
#include "eval/eval.h"
#include "model/program_builder.h"
#include "render/progress.h"
#include "scene/scene.h"
#include "scene_files.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

const char* kDefaultScene = "scenes/fig000_12b_soft_blend.json";

// Every file in tests/bad_scenes starts with "// expect: <text>": exit status 2, exactly one
// line on stderr naming the place and containing <text>, and no output file. (Its folders hold
// what those scenes read, such as the mesh files in meshes/.)
TEST(BadScenes, OneLocatedLineExitTwoNoOutput) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(source_path("tests/bad_scenes"))) {
    if (entry.is_directory()) continue;
    const std::string path = entry.path().string(), text = read_file(path);
    ASSERT_EQ(text.rfind("// expect: ", 0), 0u) << path << " has no '// expect:' first line";
    // Some files have CR LF or CR-only line endings: the first line ends at either.
    const std::string expect = text.substr(11, text.find_first_of("\r\n") - 11);
    const std::string dir = temp_dir("bad_scene");
    const RunResult r = run_softtrace("render " + path + " -o " + dir + "/out.exr");
    EXPECT_EQ(r.status, 2) << path;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << path << ": " << r.err;
    EXPECT_EQ(r.err.rfind("softtrace: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos)
        << path << "\n  expected: " << expect << "\n  got: " << r.err;
    EXPECT_TRUE(fs::is_empty(dir)) << path << " left a file behind";
    ++count;
  }
  EXPECT_GE(count, 10);
}

TEST(Output, UnwritableOrMissingFolderIsReportedBeforeRendering) {
  const RunResult r = run_softtrace(std::string("render ") + source_path(kDefaultScene) +
                                    " -o /nonexistent-folder/x.exr --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(
      r.err.find("/nonexistent-folder/x.exr: the folder '/nonexistent-folder' does not exist"),
      std::string::npos)
      << r.err;
  const RunResult bad_ext = run_softtrace(std::string("render ") + source_path(kDefaultScene) +
                                          " -o " + temp_dir("ext") + "/x.tiff --quiet");
  EXPECT_EQ(bad_ext.status, 2);
  EXPECT_NE(bad_ext.err.find("unsupported output format '.tiff'"), std::string::npos);
}

TEST(Output, ExistingFileSurvivesABadScene) {
  const std::string dir = temp_dir("keep");
  const std::string out = dir + "/precious.exr";
  std::ofstream(out) << "precious";
  const RunResult r =
      run_softtrace("render " + source_path("tests/bad_scenes/unknown_key.json") + " -o " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(read_file(out), "precious");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(Usage, HelpAndBadOptions) {
  const RunResult help = run_softtrace("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("render"), std::string::npos);
  EXPECT_NE(help.out.find("eval"), std::string::npos);
  EXPECT_EQ(run_softtrace("render --help").status, 0);
  EXPECT_EQ(run_softtrace("").status, 2);
  EXPECT_EQ(run_softtrace("render").status, 2);
  EXPECT_EQ(
      run_softtrace(std::string("render ") + source_path(kDefaultScene) + " --width 0").status, 2);
  EXPECT_EQ(run_softtrace(std::string("render ") + source_path(kDefaultScene) +
                          " --aov depth,bogus -o " + temp_dir("aov") + "/x.exr")
                .status,
            2);
}

// `--version` alone takes a short path past the parser (command_line.cpp); with more words the
// whole parser answers. Both give the same one line on stdout, nothing on stderr, and exit 0.
TEST(Usage, VersionAloneIsTheParsersAnswer) {
  const RunResult alone = run_softtrace("--version");
  const RunResult parsed = run_softtrace("--version --version");
  EXPECT_EQ(alone.status, 0);
  EXPECT_EQ(parsed.status, 0);
  EXPECT_TRUE(std::regex_match(alone.out, std::regex("softtrace [0-9.]+ \\(commit [0-9a-f]+\\)\n")))
      << alone.out;
  EXPECT_EQ(alone.out, parsed.out);
  EXPECT_EQ(alone.err, "");
  EXPECT_EQ(parsed.err, "");
  // Not a subcommand's option: refused by the parser as before.
  EXPECT_EQ(run_softtrace("render --version").status, 2);
}

// A misspelled subcommand or option is named, with the nearest known one (edit distance <= 2,
// swaps of neighbours counting 1), on one line with exit 2.
TEST(Usage, MisspellingsAreNamedWithTheNearestKnownWord) {
  const std::string scene = " " + source_path(kDefaultScene);
  const std::pair<std::string, std::string> cases[] = {
      {"rendr" + scene, "softtrace: unknown command 'rendr' (did you mean 'render'?)\n"},
      {"rneder" + scene, "softtrace: unknown command 'rneder' (did you mean 'render'?)\n"},
      {"evl" + scene, "softtrace: unknown command 'evl' (did you mean 'eval'?)\n"},
      {"paint" + scene, "softtrace: unknown command 'paint' (see softtrace --help)\n"},
      {"render" + scene + " --widht 8",
       "softtrace: unknown option '--widht' (did you mean '--width'?)\n"},
      {"render" + scene + " --wdith=8",
       "softtrace: unknown option '--wdith' (did you mean '--width'?)\n"},
      {"bench" + scene + " --repet 2",
       "softtrace: unknown option '--repet' (did you mean '--repeat'?)\n"},
      {"render" + scene + " -x", "softtrace: unknown option '-x' (see softtrace render --help)\n"},
      {"render" + scene + " -width 8",
       "softtrace: unknown option '-width' (did you mean '--width'?)\n"},
      {"eval" + scene + " --width 8",
       "softtrace: unknown option '--width' (see softtrace eval --help)\n"},
      {"--hepl", "softtrace: unknown option '--hepl' (did you mean '--help'?)\n"},
  };
  for (const auto& [args, expected] : cases) {
    const RunResult r = run_softtrace(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err, expected) << args;
  }
  // Known words with a bad value get the value's rule (test_cli_options.cpp has every option).
  const RunResult range = run_softtrace("render" + scene + " --width 0");
  EXPECT_EQ(range.err,
            "softtrace: --width: expected an integer from 1 to 16384, got '0' (see softtrace "
            "--help)\n");
}

// The Fig. 12(b) field written out independently of fieldlib (docs/math.md §3.2, 000 Eqs. 19-20).
double blanc0(double d) {
  if (d >= 1) return 0;
  if (d <= 0.5) return 1 - 2 * d * d;
  return (1 - d * d) * (1 - d * d) / (0.75 + 1.5 * d * d);
}
double fig12b(double x, double y, double z) {
  const double h = std::abs(x / 8) + std::abs(y / 8);  // n1 = 1
  const double d1 = std::pow(std::pow(h, 20) + std::pow(std::abs(z / 24), 20), 1.0 / 20);
  const double d2 = std::pow(std::pow(std::abs(x / 30), 20) + std::pow(std::abs(y / 30), 20) +
                                 std::pow(std::abs(z / 12), 20),
                             1.0 / 20);
  return blanc0(d1) + blanc0(d2);
}

TEST(Eval, MatchesTheFormulas) {
  const std::string dir = temp_dir("eval");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-20, 20);
  std::vector<std::array<double, 3>> pts;
  {
    std::ofstream f(dir + "/points.txt");
    f.precision(17);
    for (int i = 0; i < 200; ++i) {
      const std::array<double, 3> p{u(rng), u(rng), 0.7 * u(rng)};
      pts.push_back(p);
      f << p[0] << " " << p[1] << " " << p[2] << "\n";
    }
  }
  const RunResult r = run_softtrace(std::string("eval ") + source_path(kDefaultScene) +
                                    " --points " + dir + "/points.txt");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream out(r.out);
  int nonzero = 0;
  for (const auto& p : pts) {
    double v, gx, gy, gz;
    ASSERT_TRUE(out >> v >> gx >> gy >> gz);
    // The text round trip loses nothing: %.17g.
    ASSERT_NEAR(v, fig12b(p[0], p[1], p[2]), 1e-12);
    const double h = 1e-6;
    const double fd[3] = {(fig12b(p[0] + h, p[1], p[2]) - fig12b(p[0] - h, p[1], p[2])) / (2 * h),
                          (fig12b(p[0], p[1] + h, p[2]) - fig12b(p[0], p[1] - h, p[2])) / (2 * h),
                          (fig12b(p[0], p[1], p[2] + h) - fig12b(p[0], p[1], p[2] - h)) / (2 * h)};
    EXPECT_NEAR(gx, fd[0], 1e-5);
    EXPECT_NEAR(gy, fd[1], 1e-5);
    EXPECT_NEAR(gz, fd[2], 1e-5);
    nonzero += v > 0;
  }
  EXPECT_GT(nonzero, 50);

  std::ofstream(dir + "/bad.txt") << "1 2 3\n1 2\n";
  const RunResult bad = run_softtrace(std::string("eval ") + source_path(kDefaultScene) +
                                      " --points " + dir + "/bad.txt");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("bad.txt:2: expected three finite numbers"), std::string::npos) << bad.err;
}

OIIO::ImageBuf read_with_oiio(const std::string& path) {
  OIIO::ImageBuf b(path);
  b.read(0, 0, true, OIIO::TypeDesc::FLOAT);
  return b;
}

TEST(Render, AovChannelsAndSameBitsForAnyThreadCount) {
  const std::string dir = temp_dir("threads");
  const std::string base =
      std::string("render ") + source_path(kDefaultScene) +
      " --width 96 --height 72 --spp 2 --quiet --aov depth,normal,steps,albedo";
  ASSERT_EQ(run_softtrace(base + " --threads 1 -o " + dir + "/t1.exr").status, 0);
  ASSERT_EQ(run_softtrace(base + " --threads 2 -o " + dir + "/t2.exr").status, 0);
  ASSERT_EQ(
      run_softtrace(base + " --threads 2 -o " + dir + "/t2b.exr -o " + dir + "/t2.png").status, 0);

  const OIIO::ImageBuf a = read_with_oiio(dir + "/t1.exr"), b = read_with_oiio(dir + "/t2.exr"),
                       c = read_with_oiio(dir + "/t2b.exr");
  const std::vector<std::string> expected = {
      "R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "steps", "albedo.R", "albedo.G", "albedo.B"};
  std::vector<std::string> names = a.spec().channelnames;
  std::sort(names.begin(), names.end());
  std::vector<std::string> sorted = expected;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(names, sorted);
  ASSERT_EQ(a.spec().image_pixels(), 96u * 72u);
  std::vector<float> pa(a.spec().image_pixels() * a.nchannels()), pb(pa.size()), pc(pa.size());
  a.get_pixels(a.roi(), OIIO::TypeDesc::FLOAT, pa.data());
  b.get_pixels(b.roi(), OIIO::TypeDesc::FLOAT, pb.data());
  c.get_pixels(c.roi(), OIIO::TypeDesc::FLOAT, pc.data());
  EXPECT_EQ(0, std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)))
      << "--threads 1 and --threads 2 differ";
  EXPECT_EQ(0, std::memcmp(pb.data(), pc.data(), pb.size() * sizeof(float)))
      << "two runs in a row differ";
  int hits = 0, nonfinite = 0, edges = 0;
  const int zc = a.spec().channelindex("Z"), ac = a.spec().channelindex("A");
  const int nx = a.spec().channelindex("N.X");
  for (size_t i = 0; i < a.spec().image_pixels(); ++i) {
    const float* p = &pa[i * a.nchannels()];
    hits += p[ac] > 0;
    for (int k = 0; k < a.nchannels(); ++k)
      if (k != zc && !std::isfinite(p[k])) ++nonfinite;
    // The normal is the mean of the pixel's 2 samples: where only one meets the object it is
    // half a unit normal (as the albedo is half the colour and A is 1/2).
    const double n2 =
        double(p[nx]) * p[nx] + double(p[nx + 1]) * p[nx + 1] + double(p[nx + 2]) * p[nx + 2];
    if (p[ac] == 0.5f) {
      ++edges;
      EXPECT_NEAR(n2, 0.25, 1e-5) << "pixel " << i;
    }
  }
  EXPECT_GT(hits, 96 * 72 / 5) << "the object should cover a good part of the frame";
  EXPECT_GT(edges, 10) << "half-covered pixels along the silhouette";
  EXPECT_EQ(nonfinite, 0);
  EXPECT_TRUE(fs::exists(dir + "/t2.png"));
}

// Directions scaled by 1e308 or 1e-300 are the same directions: the picture is the same bits
// (a light direction of 1e308 once overflowed its length and left the lit side black).
TEST(Render, HugeOrTinyDirectionsGiveTheSamePicture) {
  const std::string dir = temp_dir("scaled_directions");
  const std::string scene = read_file(source_path(kDefaultScene));
  const auto variant = [&](const std::string& name, const std::string& from,
                           const std::string& to) {
    const size_t at = scene.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    std::ofstream(dir + "/" + name + ".json") << std::string(scene).replace(at, from.size(), to);
    return dir + "/" + name + ".json";
  };
  const std::string light = "\"direction\": [1.0, 0.35, -1.0]", up = "\"up\": [0, 0, 1]";
  const std::string scenes[] = {
      source_path(kDefaultScene),
      variant("light_huge", light, "\"direction\": [1e308, 0.35e308, -1e308]"),
      variant("light_tiny", light, "\"direction\": [1e-300, 0.35e-300, -1e-300]"),
      variant("up_huge", up, "\"up\": [0, 0, 1.7e308]"),
      variant("up_tiny", up, "\"up\": [0, 0, 4e-320]"),
  };
  for (size_t i = 0; i < std::size(scenes); ++i) {
    const RunResult r =
        run_softtrace("render " + scenes[i] + " --width 64 --height 48 --spp 1 --quiet -o " + dir +
                      "/" + std::to_string(i) + ".exr");
    ASSERT_EQ(r.status, 0) << scenes[i] << ": " << r.err;
    if (i == 0) continue;
    const RunResult d =
        run_softtrace("diff --fail 0 " + dir + "/0.exr " + dir + "/" + std::to_string(i) + ".exr");
    EXPECT_EQ(d.status, 0) << scenes[i] << ":\n" << d.out;
  }
}

// `eval` on every scene prints exactly (%.17g round trip) what the library computes for the
// scene's first object with a field; the library's values are checked against the formulas by the
// node sweep, the property tests and the figure tests.
TEST(Eval, EveryScenePrintsTheLibraryValues) {
  int scenes = 0;
  for (const auto& file : scene_files()) {
    const std::string path = file.string();
    const Scene scene = load_scene(path);
    const auto field = std::find_if(scene.objects.begin(), scene.objects.end(),
                                    [](const SceneObject& o) { return o.field != nullptr; });
    if (field == scene.objects.end()) continue;  // only shapes and CSGs: nothing to evaluate
    const SceneObject& obj = *field;
    const std::string dir = temp_dir("eval_all");
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> pts;
    {
      std::ofstream f(dir + "/p.txt");
      f.precision(17);
      for (int i = 0; i < 40; ++i) {
        const Box& b = obj.bounds;
        pts.push_back({b.lo.x + u(rng) * b.extent().x, b.lo.y + u(rng) * b.extent().y,
                       b.lo.z + u(rng) * b.extent().z});
        f << pts.back().x << " " << pts.back().y << " " << pts.back().z << "\n";
      }
    }
    const RunResult r = run_softtrace("eval " + path + " --points " + dir + "/p.txt");
    ASSERT_EQ(r.status, 0) << path << ": " << r.err;
    std::istringstream out(r.out);
    const Program program = compile(*obj.field);
    Workspace ws;
    // Exactly the compiled program's values, and the model tree's to 1e-12 relative (the
    // gradient through nested rotations is summed in another order).
    const auto near = [](double a, double b) {
      return a == b || std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b));
    };
    for (const Vec3& p : pts) {
      double v, gx, gy, gz;
      ASSERT_TRUE(out >> v >> gx >> gy >> gz) << path;
      Vec3 g, gm;
      EXPECT_EQ(v, evaluate(program, p, &g, ws)) << path;
      EXPECT_EQ(gx, g.x) << path;
      EXPECT_EQ(gy, g.y) << path;
      EXPECT_EQ(gz, g.z) << path;
      EXPECT_TRUE(near(v, obj.field->eval(p, &gm))) << path;
      EXPECT_TRUE(near(g.x, gm.x) && near(g.y, gm.y) && near(g.z, gm.z))
          << path << ": " << g.x << " " << gm.x;
    }
    ++scenes;
  }
  EXPECT_GE(scenes, 30);
}

TEST(Bench, JsonReportsThroughput) {
  const RunResult r = run_softtrace(std::string("bench ") + source_path(kDefaultScene) +
                                    " --width 32 --height 24 --repeat 2 --threads 1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("schema"), 1);
  EXPECT_FALSE(j.at("commit").get<std::string>().empty());
  EXPECT_EQ(j.at("width"), 32);
  EXPECT_EQ(j.at("threads"), 1);
  EXPECT_EQ(j.at("repeat"), 2);
  ASSERT_EQ(j.at("frames").size(), 2u);
  for (const auto& f : j.at("frames")) {
    EXPECT_GT(f.at("wall_s").get<double>(), 0);
    EXPECT_GT(f.at("cpu_s").get<double>(), 0);
    EXPECT_GT(f.at("mrays_per_s").get<double>(), 0);
  }
  EXPECT_GT(j.at("mrays_per_s").get<double>(), 0);
  EXPECT_GT(j.at("evaluations_per_ray").get<double>(), 1);
  EXPECT_LE(j.at("best_s").get<double>(), j.at("median_s").get<double>());

  // The work per ray that enters a box adds up to the evaluations per primary ray.
  const auto& p = j.at("primary");
  const auto& s = j.at("shadow");
  EXPECT_EQ(p.at("rays"), 32 * 24 * j.at("spp").get<int>());
  EXPECT_GT(p.at("entered_box").get<long long>(), 0);
  EXPECT_LE(p.at("entered_box").get<long long>(), p.at("rays").get<long long>());
  EXPECT_GT(s.at("rays").get<long long>(), 0) << "the default scene's light casts shadows";
  for (const auto* w : {&p, &s}) {
    EXPECT_GE(w->at("point_evals").get<double>(), w->at("refine_iterations").get<double>());
    EXPECT_GE(w->at("box_evals").get<double>(), 1);
    EXPECT_NEAR(w->at("evaluations").get<double>(),
                w->at("point_evals").get<double>() + w->at("box_evals").get<double>(), 1e-9);
  }
  const double total = p.at("evaluations").get<double>() * p.at("entered_box").get<double>() +
                       s.at("evaluations").get<double>() * s.at("entered_box").get<double>();
  EXPECT_NEAR(total / p.at("rays").get<double>(), j.at("evaluations_per_ray").get<double>(), 1e-6);
}

// Without --json: one line per frame with wall and CPU time, then the work per ray of each kind.
TEST(Bench, TextReportsEveryFrameAndTheWorkPerRay) {
  const RunResult r = run_softtrace(std::string("bench ") + source_path(kDefaultScene) +
                                    " --width 16 --height 12 --repeat 2 --threads 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("16x12, 4 spp, 2 threads, lipschitz local, commit "), std::string::npos)
      << r.out;
  for (const char* re :
       {R"(  frame 1: wall \d+\.\d{4} s, cpu \d+\.\d{4} s, )", R"(  frame 2: wall )",
        R"(  primary rays: 768, \d+ enter a box; per such ray \d+\.\d\d point \+ )",
        R"(  shadow rays: \d+, \d+ enter a box; )"})
    EXPECT_TRUE(std::regex_search(r.out, std::regex(re))) << re << "\n" << r.out;
}

// A lens's blur_samples beyond the image's spp are what each pixel takes: the summary line's spp
// is that count, the one its rays/s counts (shapes_blob_floor_dof: spp 4, blur_samples 16).
TEST(Render, SummaryNamesTheSamplesEachPixelTakes) {
  const RunResult r =
      run_softtrace(std::string("render ") + source_path("scenes/shapes_blob_floor_dof.json") +
                    " --width 8 --height 6 --threads 2 -o " + temp_dir("summary_spp") + "/x.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.rfind("8x6, 16 spp in ", 0), 0u) << r.err;
}

// The progress bar (on a terminal, or forced with --progress) shows the primary-ray rate, the
// time elapsed and the time left; --quiet or a non-terminal stderr shows none.
TEST(Progress, RenderAndBenchShowRateElapsedAndTimeLeft) {
  const std::string dir = temp_dir("progress");
  const std::string scene = " " + source_path(kDefaultScene) + " --width 32 --height 24";
  const std::regex first(R"(\w+ \[ {40}\]   0%       \? Mrays/s \(\d+\.\ds\|\?\) *)");
  const std::regex last(R"(\w+ \[={40}\] 100% +\d+\.\d\d Mrays/s \(\d+\.\ds\|0\.0s\) *)");
  for (const std::string& cmd :
       {"render" + scene + " --spp 2 -o " + dir + "/x.exr", "bench" + scene + " --repeat 2"}) {
    const RunResult r = run_softtrace(cmd + " --progress");
    ASSERT_EQ(r.status, 0) << cmd << ": " << r.err;
    ASSERT_EQ(r.err.rfind('\r', 0), 0u) << cmd << ": " << r.err;
    const std::string bar = r.err.substr(1, r.err.find('\n') - 1);
    const std::string label = cmd.substr(0, 5) == "bench" ? "bench " : "rendering ";
    EXPECT_EQ(bar.rfind(label, 0), 0u) << bar;
    EXPECT_TRUE(std::regex_match(bar.substr(0, bar.find('\r')), first)) << bar;
    EXPECT_TRUE(std::regex_match(bar.substr(bar.rfind('\r') + 1), last)) << bar;

    const RunResult plain = run_softtrace(cmd);
    EXPECT_EQ(plain.err.find('['), std::string::npos) << "no bar off a terminal: " << plain.err;
    EXPECT_EQ(run_softtrace(cmd + " --progress --quiet").status, 2);
  }
  EXPECT_EQ(Progress::duration(0.44), "0.4s");
  EXPECT_EQ(Progress::duration(59.94), "59.9s");
  EXPECT_EQ(Progress::duration(187.2), "3m07s");
  EXPECT_EQ(Progress::duration(7500), "2h05m");
}

// Both commands that build a film refuse frames above 2^26 pixels before allocating it.
TEST(Cli, RenderAndBenchRefuseHugeFrames) {
  const std::string dir = temp_dir("huge");
  for (const std::string cmd : {"render", "bench"}) {
    const std::string out = cmd == "render" ? " -o " + dir + "/x.exr" : "";
    const RunResult r = run_softtrace(cmd + " " + source_path(kDefaultScene) +
                                      " --width 16384 --height 8192" + out);
    EXPECT_EQ(r.status, 2) << cmd;
    EXPECT_NE(r.err.find(": /image: more than 2^26 pixels requested"), std::string::npos)
        << cmd << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.exr"));
}

}  // namespace
}  // namespace softtrace::test

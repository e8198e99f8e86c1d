// Every option's refusal in our words: one line naming the option, the value and the rule, exit
// status 2, nothing written; CLI11's internals ("Check foo value in {global->1,local->0} OR
// {1,0} FAILED", "Value 0 not in range", "1 required INT missing") never reach the user. And
// the image size options: --width or --height alone keeps the scene's aspect, --scale scales
// both, and a frame that shows nothing warns.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.h"

namespace softtrace::test {
namespace {

struct Refusal {
  std::string args;      // after "softtrace "; SCENE, IMG and OUT are replaced
  std::string expected;  // the whole stderr line after "softtrace: "
};

std::string substitute(std::string text, const std::string& word, const std::string& by) {
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + by.size()))
    text.replace(at, word.size(), by);
  return text;
}

TEST(CliOptions, EveryOptionRefusesABadValueInOurWords) {
  const std::string dir = temp_dir("cli_options");
  const std::string scene = source_path(kDefaultScene), img = dir + "/img.png";
  ASSERT_EQ(run_softtrace("render " + scene + " --width 8 --height 6 -q -o " + img).status, 0);
  const std::string usage = " (see softtrace --help)";
  const Refusal cases[] = {
      // render
      {"render SCENE --width 0", "--width: expected an integer from 1 to 16384, got '0'" + usage},
      {"render SCENE --width 16385",
       "--width: expected an integer from 1 to 16384, got '16385'" + usage},
      {"render SCENE --width 8.5",
       "--width: expected an integer from 1 to 16384, got '8.5'" + usage},
      {"render SCENE --height x", "--height: expected an integer from 1 to 16384, got 'x'" + usage},
      {"render SCENE --scale 0", "--scale: expected a finite number > 0, got '0'" + usage},
      {"render SCENE --scale inf", "--scale: expected a finite number > 0, got 'inf'" + usage},
      {"render SCENE --scale 100 -o OUT",
       "--scale 100: keeping the scene's aspect gives an image width of 64000 pixels (expected 1 "
       "to 16384)"},
      {"render SCENE --height 16000 -o OUT",
       "--height 16000: keeping the scene's aspect gives an image width of 21333 pixels"
       " (expected 1 to 16384)"},
      {"render SCENE --scale 2 --width 8", "--width excludes --scale" + usage},
      {"render SCENE --spp 0", "--spp: expected an integer from 1 to 4096, got '0'" + usage},
      {"render SCENE --antialias -1",
       "--antialias: expected a number from 0 to 1e+06, got '-1'" + usage},
      {"render SCENE --threads 1025",
       "--threads: expected an integer from 1 to 1024, got '1025'" + usage},
      {"render SCENE --lipschitz foo", "--lipschitz: expected local or global, got 'foo'" + usage},
      {"render SCENE --lipschitz 1", "--lipschitz: expected local or global, got '1'" + usage},
      {"render SCENE --frame 1e3",
       "--frame: expected an integer from 0 to 999999, got '1e3'" + usage},
      {"render SCENE --frame -1",
       "--frame: expected an integer from 0 to 999999, got '-1'" + usage},
      {"render SCENE --aov depth,colour",
       "--aov: unknown AOV 'colour' (expected depth, normal, steps, albedo)" + usage},
      {"render SCENE --crop 0.5,0.2,0,1 -o OUT",
       "--crop '0.5,0.2,0,1': expected 0 <= X0 < X1 <= 1 and 0 <= Y0 < Y1 <= 1"},
      {"render SCENE --pixel-bounds 1,2 -o OUT", "--pixel-bounds '1,2': expected X0,X1,Y0,Y1"},
      {"render SCENE --tile 2/1 -o OUT",
       "--tile '2/1': expected I/N, whole numbers with 0 <= I < N <= 2^31 - 1 (tiles are numbered "
       "from 0)"},
      {"render SCENE -o DIR/x.jpg",
       "DIR/x.jpg: unsupported output format '.jpg' (expected .exr or .png)"},
      {"render SCENE --quiet --progress", "--quiet excludes --progress" + usage},
      {"render SCENE --progress=2", "--progress: a flag takes no value" + usage},
      {"render SCENE --output", "--output: expected a value after it" + usage},
      {"render SCENE --half=1", "--half: a flag takes no value" + usage},
      {"render SCENE --png-alpha=x", "--png-alpha: a flag takes no value" + usage},
      {"render SCENE --eye foo", "--eye: expected X,Y,Z (three finite numbers), got 'foo'" + usage},
      {"render SCENE --target 1,2,x",
       "--target: expected X,Y,Z (three finite numbers), got '1,2,x'" + usage},
      {"render SCENE --fov foo", "--fov: expected a finite number, got 'foo'" + usage},
      {"render SCENE --fov 0", "--fov: expected a vertical field of view in (0, 180) degrees"},
      {"render SCENE --width", "--width: expected a value after it" + usage},
      {"render SCENE --width 3 --width 4", "--width: given more than once" + usage},
      {"render SCENE extra", "unexpected argument 'extra'" + usage},
      {"render SCENE --flatten=0", "--flatten: a flag takes no value" + usage},
      {"render SCENE --quiet=foo", "--quiet: a flag takes no value" + usage},
      {"diff IMG IMG --abs=x", "--abs: a flag takes no value" + usage},
      {"nodes --dict=2", "--dict: a flag takes no value" + usage},
      {"render", "scene is required" + usage},
      // eval
      {"eval SCENE --object nope", scene + ": no object named 'nope'"},
      {"eval SCENE --points DIR/none.txt", dir + "/none.txt: cannot open the points file"},
      // mesh
      {"mesh SCENE -o DIR/m.obj --cells 0",
       "--cells: expected an integer from 1 to 65536, got '0'" + usage},
      {"mesh SCENE -o DIR/m.obj --cells 1e3",
       "--cells: expected an integer from 1 to 65536, got '1e3'" + usage},
      {"mesh SCENE -o DIR/m.obj --voxel -1",
       "--voxel: expected a finite number > 0, got '-1'" + usage},
      {"mesh SCENE -o DIR/m.obj --voxel nan",
       "--voxel: expected a finite number > 0, got 'nan'" + usage},
      {"mesh SCENE -o DIR/m.obj --threads 0",
       "--threads: expected an integer from 1 to 1024, got '0'" + usage},
      {"mesh SCENE", "--output is required" + usage},
      {"mesh SCENE -o DIR/m.obj --object", "--object: expected a value after it" + usage},
      {"mesh SCENE -o DIR/m.obj --bounds 1,2,3",
       "--bounds '1,2,3': expected six numbers x0,x1,y0,y1,z0,z1"},
      {"mesh SCENE -o DIR/m.obj --quiet=x", "--quiet: a flag takes no value" + usage},
      {"mesh SCENE -o DIR/m.obj --progress=x", "--progress: a flag takes no value" + usage},
      // diff
      {"diff IMG IMG --fail -1", "--fail: expected a number >= 0, got '-1'" + usage},
      {"diff IMG IMG --failpercent 101",
       "--failpercent: expected a number from 0 to 100, got '101'" + usage},
      {"diff IMG IMG --failrelative nan",
       "--failrelative: expected a number >= 0, got 'nan'" + usage},
      {"diff IMG IMG --hardfail x", "--hardfail: expected a number >= 0, got 'x'" + usage},
      {"diff IMG IMG --allowfailures -1",
       "--allowfailures: expected an integer >= 0, got '-1'" + usage},
      {"diff IMG IMG --warn -0.5", "--warn: expected a number >= 0, got '-0.5'" + usage},
      {"diff IMG IMG --warnpercent -1",
       "--warnpercent: expected a number from 0 to 100, got '-1'" + usage},
      {"diff IMG IMG --warnrelative y", "--warnrelative: expected a number >= 0, got 'y'" + usage},
      {"diff IMG IMG --hardwarn -1", "--hardwarn: expected a number >= 0, got '-1'" + usage},
      {"diff IMG IMG --scale nan", "--scale: expected a finite number, got 'nan'" + usage},
      {"diff IMG IMG --channels Q", "--channels: 'Q' is not in both images (R,G,B vs R,G,B)"},
      {"diff IMG IMG -o DIR/d.tif",
       "DIR/d.tif: unsupported output format '.tif' (expected .exr or .png)"},
      {"diff IMG", "b is required" + usage},
      {"diff IMG IMG --od=1", "--od: a flag takes no value" + usage},
      {"diff IMG IMG --quiet=1", "--quiet: a flag takes no value" + usage},
      {"diff IMG IMG --out", "--out: expected a value after it" + usage},
      // bench
      {"bench SCENE --width 0", "--width: expected an integer from 1 to 16384, got '0'" + usage},
      {"bench SCENE --height 0", "--height: expected an integer from 1 to 16384, got '0'" + usage},
      {"bench SCENE --scale -1", "--scale: expected a finite number > 0, got '-1'" + usage},
      {"bench SCENE --threads 0", "--threads: expected an integer from 1 to 1024, got '0'" + usage},
      {"bench SCENE --repeat 0", "--repeat: expected an integer from 1 to 1000, got '0'" + usage},
      {"bench SCENE --lipschitz Global2",
       "--lipschitz: expected local or global, got 'Global2'" + usage},
      {"bench SCENE --json=1", "--json: a flag takes no value" + usage},
      {"bench SCENE --quiet=1", "--quiet: a flag takes no value" + usage},
      {"bench SCENE --progress=1", "--progress: a flag takes no value" + usage},
      {"bench SCENE --eye foo", "--eye: expected X,Y,Z (three finite numbers), got 'foo'" + usage},
      {"bench SCENE --target 1,2,x",
       "--target: expected X,Y,Z (three finite numbers), got '1,2,x'" + usage},
      {"bench SCENE --fov 0", "--fov: expected a vertical field of view in (0, 180) degrees"},
      // merge, nodes, no command
      {"merge IMG", "--output is required" + usage},
      {"merge IMG -o DIR/m.exr --quiet=2", "--quiet: a flag takes no value" + usage},
      {"nodes extra", "unexpected argument 'extra'" + usage},
      {"", "expected a command: render, eval, mesh, diff, bench, merge or nodes" + usage},
  };
  for (const Refusal& c : cases) {
    std::string args = substitute(c.args, "SCENE", scene);
    args = substitute(substitute(args, "IMG", img), "OUT", dir + "/out.exr");
    args = substitute(args, "DIR", dir);
    const std::string expected = substitute(c.expected, "DIR", dir);
    const RunResult r = run_softtrace(args + " </dev/null");
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.err, "softtrace: " + expected + "\n") << args;
    EXPECT_EQ(r.out, "") << args;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));

  // Every option each command's --help lists has a case above (named in its arguments, or a
  // required one in its message), so that an option added later comes with its refusal.
  for (const std::string command : {"render", "eval", "mesh", "diff", "bench", "merge", "nodes"}) {
    std::istringstream help(run_softtrace(command + " --help").out);
    int options = 0;
    for (std::string line; std::getline(help, line);) {
      if (line.rfind("  -", 0) != 0) continue;  // an option's line: "  -o,--output TEXT ..."
      std::istringstream words(line);
      std::string names;
      words >> names;
      if (names == "-h,--help" || names == "--help-all" || names == "-v,-a") continue;  // no value
      std::vector<std::string> aliases;  // "-o,--output": -o and --output
      std::istringstream split(names);
      for (std::string alias; std::getline(split, alias, ',');) aliases.push_back(alias);
      const std::string& name = aliases.back();
      bool covered = false;
      for (const Refusal& c : cases) {
        std::istringstream args(c.args);
        std::string word;
        args >> word;
        if (word != command) continue;
        while (args >> word)
          for (const std::string& alias : aliases)
            covered |= word == alias || word.rfind(alias + "=", 0) == 0;
        covered |= c.expected.rfind(name + " is required", 0) == 0;
      }
      EXPECT_TRUE(covered) << command << " " << name << " has no refusal case";
      ++options;
    }
    EXPECT_GT(options, 0) << command;
  }
}

// The size of a written PNG.
std::pair<int, int> png_size(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return {0, 0};
  return {in->spec().width, in->spec().height};
}

// The scene is 640x480, its camera's fov vertical: a width alone must not widen the view.
TEST(CliOptions, OneSideAloneKeepsTheScenesAspectAndScaleScalesBoth) {
  const std::string dir = temp_dir("cli_size");
  const std::string render = "render " + source_path(kDefaultScene) + " -q --spp 1 -o " + dir;
  const struct {
    std::string options;
    int width, height;
  } cases[] = {
      {"--width 64", 64, 48},
      {"--height 30", 40, 30},
      {"--width 65", 65, 49},
      {"--scale 0.1", 64, 48},
      {"--width 50 --height 10", 50, 10},
      {"--scale 0.001", 1, 1},
  };
  for (const auto& c : cases) {
    const RunResult r = run_softtrace(render + "/x.png " + c.options);
    ASSERT_EQ(r.status, 0) << c.options << ": " << r.err;
    EXPECT_EQ(png_size(dir + "/x.png"), std::make_pair(c.width, c.height)) << c.options;
  }
  const RunResult bench =
      run_softtrace("bench " + source_path(kDefaultScene) + " -q --repeat 1 --width 32");
  ASSERT_EQ(bench.status, 0) << bench.err;
  EXPECT_NE(bench.out.find(": 32x24,"), std::string::npos) << bench.out;
}

// bench moves the camera as render does: looking away from the scene, no primary ray enters an
// object's box; zoomed in on it, every one does, where the scene's view leaves a few outside.
TEST(CliOptions, BenchTakesTheCameraOptions) {
  const auto entered = [&](const std::string& view) {
    const RunResult r = run_softtrace("bench " + source_path(kDefaultScene) +
                                      " -q --repeat 1 --width 32 --json" + view);
    EXPECT_EQ(r.status, 0) << view << ": " << r.err;
    return r.status == 0 ? nlohmann::json::parse(r.out)["primary"]["entered_box"].get<long>() : -1;
  };
  const long rays = 32 * 24 * 4;  // the scene's 4 spp
  const long scene_view = entered("");
  EXPECT_GT(scene_view, rays / 4);
  EXPECT_LT(scene_view, rays);
  EXPECT_EQ(entered(" --fov 5"), rays);
  EXPECT_EQ(entered(" --eye 500,0,0 --target 1000,0,0"), 0);
}

TEST(CliOptions, AFrameThatShowsNothingWarnsAndStillWrites) {
  const std::string dir = temp_dir("cli_empty");
  const std::string away = source_path("tests/scenes/nothing_in_view.json");
  const std::string warning =
      "softtrace: warning: no object is visible in the frame, the image shows only the "
      "background (check the camera's eye, target and fov against the objects)\n";
  for (const std::string quiet : {"", " -q"}) {
    const RunResult r = run_softtrace("render " + away + quiet + " -o " + dir + "/away.png");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.rfind(warning, 0), 0u) << quiet << ": " << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/away.png"));
  }
  // A picture with something in it, or a part of the frame, says nothing of the kind.
  const RunResult seen = run_softtrace("render " + source_path(kDefaultScene) +
                                       " -q --width 16 -o " + dir + "/seen.png");
  EXPECT_EQ(seen.status, 0);
  EXPECT_EQ(seen.err, "");
  const RunResult part = run_softtrace("render " + away + " -q --tile 0/2 -o " + dir + "/part.exr");
  EXPECT_EQ(part.status, 0);
  EXPECT_EQ(part.err, "");
}

}  // namespace
}  // namespace softtrace::test

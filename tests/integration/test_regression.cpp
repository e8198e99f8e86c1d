// The image-regression harness itself: every scene is covered, a changed scene fails with a page
// to look at, and renders are the same bits for any thread count at the regression size.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_util.h"

namespace softtrace::test {
namespace {

namespace fs = std::filesystem;

struct Entry {
  std::string name;
  int width = 0, height = 0;
};

// SOFTTRACE_REGRESSION_SCENES from tests/CMakeLists.txt, entries joined by ','.
std::vector<Entry> regression_list() {
  std::vector<Entry> list;
  std::istringstream all(SOFTTRACE_REGRESSION_LIST);
  for (std::string item; std::getline(all, item, ',');) {
    std::istringstream in(item);
    Entry e;
    in >> e.name >> e.width >> e.height;
    EXPECT_TRUE(in && e.width > 0 && e.height > 0) << "bad list entry '" << item << "'";
    list.push_back(e);
  }
  return list;
}

std::set<std::string> stems(const std::string& folder, const std::string& ext) {
  std::set<std::string> names;
  for (const auto& f : fs::directory_iterator(source_path(folder)))
    if (f.path().extension() == ext) names.insert(f.path().stem().string());
  return names;
}

TEST(Regression, ListCoversEveryScene) {
  const std::vector<Entry> list = regression_list();
  ASSERT_FALSE(list.empty());
  std::set<std::string> listed;
  for (const Entry& e : list) EXPECT_TRUE(listed.insert(e.name).second) << e.name << " twice";
  for (const std::string& scene : stems("scenes", ".json"))
    EXPECT_TRUE(listed.count(scene))
        << "scenes/" << scene << ".json has no regression test: add \"" << scene
        << " 160 120\" to SOFTTRACE_REGRESSION_SCENES (tests/CMakeLists.txt), then run "
        << "tools/bless.sh " << scene;
  for (const std::string& ref : stems("reference_images", ".exr"))
    EXPECT_TRUE(listed.count(ref))
        << "reference_images/" << ref << ".exr belongs to no listed scene";

  uintmax_t total = 0;
  for (const Entry& e : list) {
    SCOPED_TRACE(e.name);
    EXPECT_TRUE(fs::exists(source_path("scenes/" + e.name + ".json")));
    // Small renders keep the whole suite fast.
    EXPECT_LE(e.width * e.height, 320 * 240);
    const std::string ref = source_path("reference_images/" + e.name + ".exr");
    ASSERT_TRUE(fs::exists(ref)) << "no reference: run tools/bless.sh " << e.name;
    OIIO::ImageBuf buf(ref);
    ASSERT_TRUE(buf.init_spec(ref, 0, 0)) << buf.geterror();
    const OIIO::ImageSpec& spec = buf.spec();
    EXPECT_EQ(spec.width, e.width) << "the list's size changed: run tools/bless.sh " << e.name;
    EXPECT_EQ(spec.height, e.height) << "the list's size changed: run tools/bless.sh " << e.name;
    EXPECT_EQ(spec.format, OIIO::TypeDesc::HALF);
    EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
    EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
    total += fs::file_size(ref);
  }
  // Compressed half RGBA at these sizes is a few tens of kilobytes a scene.
  EXPECT_LE(total, 100u * 1024 * list.size());
}

struct Outcome {
  RunResult run;
  std::string work;
};

Outcome run_regression(const std::string& scene, const std::string& reference, const Entry& e,
                       const std::string& tag) {
  const std::string work = temp_dir("regression_" + tag);
  const RunResult r = run_command(source_path("tests/integration/regression.sh") + " " +
                                  SOFTTRACE_BIN + " " + scene + " " + reference + " " + work + " " +
                                  std::to_string(e.width) + " " + std::to_string(e.height));
  return {r, work};
}

// The first listed scene, changed slightly, against its reference: the test fails and leaves the
// render, the difference and a page with the three images and the numbers.
TEST(Regression, ChangedSceneFailsAndWritesPage) {
  const Entry e = regression_list().at(0);
  const std::string reference = source_path("reference_images/" + e.name + ".exr");
  const nlohmann::json original =
      nlohmann::json::parse(read_file(source_path("scenes/" + e.name + ".json")), nullptr, true,
                            /*ignore_comments=*/true);
  const auto variant = [&](const std::string& tag, const nlohmann::json& scene) {
    const std::string dir = temp_dir("scene_" + tag), path = dir + "/" + e.name + ".json";
    std::ofstream(path) << scene.dump(2);
    return run_regression(path, reference, e, tag);
  };

  // The copy itself passes: failures below come from the changes.
  const Outcome same = variant("same", original);
  EXPECT_EQ(same.run.status, 0) << same.run.out << same.run.err;
  EXPECT_FALSE(fs::exists(same.work + "/" + e.name + ".html"));

  nlohmann::json zoomed = original, background = original;
  zoomed["camera"]["fov"] = original["camera"]["fov"].get<double>() * 1.002;
  background["background"] = {0.5, 0.5, 0.5};
  for (const auto& [tag, scene] :
       {std::pair{std::string("zoom"), zoomed}, {"background", background}}) {
    SCOPED_TRACE(tag);
    const Outcome o = variant(tag, scene);
    EXPECT_EQ(o.run.status, 1) << o.run.out << o.run.err;
    const std::string base = o.work + "/" + e.name, html = base + ".html";
    EXPECT_NE(o.run.err.find("see " + html), std::string::npos) << o.run.err;
    EXPECT_NE(o.run.out.find("FAILURE"), std::string::npos) << o.run.out;
    EXPECT_TRUE(fs::exists(base + ".exr"));
    EXPECT_TRUE(fs::exists(base + ".diff.exr"));
    for (const char* png : {".ref.png", ".render.png", ".diff.png"}) {
      OIIO::ImageBuf img(base + png);
      ASSERT_TRUE(img.init_spec(base + png, 0, 0)) << png << ": " << img.geterror();
      EXPECT_EQ(img.spec().width, e.width);
      EXPECT_EQ(img.spec().height, e.height);
      EXPECT_EQ(img.spec().nchannels, 3);
    }
    const std::string page = read_file(html);
    for (const std::string& text :
         {e.name + ".ref.png", e.name + ".render.png", e.name + ".diff.png",
          std::string("pixels ("), std::string("FAILURE"), "tools/bless.sh " + e.name})
      EXPECT_NE(page.find(text), std::string::npos) << "page lacks " << text;
  }

  const Outcome missing = run_regression(source_path("scenes/" + e.name + ".json"),
                                         temp_dir("noref") + "/none.exr", e, "noref");
  EXPECT_EQ(missing.run.status, 1);
  EXPECT_NE(missing.run.err.find("tools/bless.sh " + e.name), std::string::npos) << missing.run.err;
}

std::vector<float> pixels(const std::string& path) {
  OIIO::ImageBuf b(path);
  EXPECT_TRUE(b.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << b.geterror();
  std::vector<float> p(b.spec().image_pixels() * b.nchannels());
  b.get_pixels(b.roi(), OIIO::TypeDesc::FLOAT, p.data());
  return p;
}

// Every listed scene at its regression size, all AOVs (12 channels): --threads 1, --threads 2
// and a second --threads 2 run give the same bits.
// Under the sanitizers, one scene in three: the rendering paths they instrument are the same for
// every scene, and the three renders of all of them cost 85 s of CPU there.
TEST(Regression, SameBitsForAnyThreadCount) {
  const std::string dir = temp_dir("regression_threads");
#ifdef SOFTTRACE_TESTS_SANITIZED
  constexpr size_t kEvery = 3;
#else
  constexpr size_t kEvery = 1;
#endif
  const std::vector<Entry> list = regression_list();
  for (size_t i = 0; i < list.size(); i += kEvery) {
    const Entry& e = list[i];
    SCOPED_TRACE(e.name);
    const std::string base = "render " + source_path("scenes/" + e.name + ".json") + " --width " +
                             std::to_string(e.width) + " --height " + std::to_string(e.height) +
                             " --spp 1 --quiet --aov depth,normal,steps,albedo";
    // One name per scene and run: OpenImageIO's image cache may hand back the spec of an
    // earlier file of the same name (its timestamps have one-second resolution).
    const std::string out = dir + "/" + e.name;
    ASSERT_EQ(run_softtrace(base + " --threads 1 -o " + out + "_t1.exr").status, 0);
    ASSERT_EQ(run_softtrace(base + " --threads 2 -o " + out + "_t2.exr").status, 0);
    ASSERT_EQ(run_softtrace(base + " --threads 2 -o " + out + "_t2b.exr").status, 0);
    const std::vector<float> a = pixels(out + "_t1.exr"), b = pixels(out + "_t2.exr"),
                             c = pixels(out + "_t2b.exr");
    ASSERT_EQ(a.size(), size_t(e.width) * e.height * 12);
    ASSERT_EQ(b.size(), a.size());
    ASSERT_EQ(c.size(), a.size());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)))
        << "--threads 1 and --threads 2 differ";
    EXPECT_EQ(0, std::memcmp(b.data(), c.data(), b.size() * sizeof(float)))
        << "two runs in a row differ";
  }
}

// A cloud of 64 polynomial blobs over a floor: more than BlobSum::kListed, so the camera rays of
// a block take their blobs from its list (tracer_blob_beam.cpp), and blocks looking past the
// cloud at the floor have empty lists.
nlohmann::json blob_cloud_over_floor() {
  nlohmann::json children = nlohmann::json::array();
  for (int i = 0; i < 64; ++i) {
    const double jx = 4 * (std::fmod(i * 0.7548776662466927, 1.0) - 0.5);
    const double jy = 4 * (std::fmod(i * 0.5698402909980532, 1.0) - 0.5);
    children.push_back(
        {{"type", "soft_object"},
         {"potential", {{"type", "murakami"}}},
         {"distance", {{"type", "lp_metric"}, {"radii", {6, 6, 6}}, {"n", 2}}},
         {"translate", {8 * (i % 4 - 1.5) + jx, 8 * (i / 4 % 4 - 1.5) + jy, 8 * (i / 16 - 1.5)}}});
  }
  return {
      {"camera", {{"eye", {70, -95, 60}}, {"target", {0, 0, 0}}, {"up", {0, 0, 1}}, {"fov", 30}}},
      {"image", {{"width", 48}, {"height", 48}, {"spp", 1}}},
      {"background", {0.45, 0.55, 0.75}},
      {"lights",
       {{{"type", "directional"},
         {"direction", {1.0, 0.35, -1.0}},
         {"intensity", 0.85},
         {"shadows", true}},
        {{"type", "ambient"}, {"intensity", 0.18}}}},
      {"objects",
       {{{"name", "cloud"},
         {"material", {{"color", {0.85, 0.8, 0.72}}}},
         {"convention", "soft"},
         {"iso", 0.5},
         {"field", {{"type", "soft_blend"}, {"children", children}}}},
        {{"shape", {{"type", "plane"}, {"distance", -26}}}}}}};
}

// A tile's pixels, all AOVs included, depend on the tile alone: the whole frame on one thread
// (each tile after others on the same thread, reusing its buffers), on two threads, and each
// 16-pixel tile rendered alone (--pixel-bounds, a fresh process) give the same bits. An empty
// blob list once decided by its vector's data() (null until a tile had filled that slot) cost
// the first tiles of a thread a BVH walk the later ones skipped: their steps differed.
TEST(Regression, EachTileAloneGivesTheSameBits) {
  const std::string dir = temp_dir("regression_tiles"), scene = dir + "/cloud.json";
  std::ofstream(scene) << blob_cloud_over_floor().dump();
  const std::string base = "render " + scene + " --quiet --aov depth,normal,steps,albedo";
  ASSERT_EQ(run_softtrace(base + " --threads 1 -o " + dir + "/whole.exr").status, 0);
  ASSERT_EQ(run_softtrace(base + " --threads 2 -o " + dir + "/whole_t2.exr").status, 0);
  const std::vector<float> whole = pixels(dir + "/whole.exr");
  ASSERT_EQ(whole.size(), 48u * 48u * 12u);
  const std::vector<float> two = pixels(dir + "/whole_t2.exr");
  ASSERT_EQ(two.size(), whole.size());
  EXPECT_EQ(0, std::memcmp(whole.data(), two.data(), whole.size() * sizeof(float)))
      << "--threads 1 and --threads 2 differ";
  const int steps = OIIO::ImageBuf(dir + "/whole.exr").spec().channelindex("steps");
  ASSERT_GE(steps, 0);
  float most = 0;
  for (size_t i = size_t(steps); i < whole.size(); i += 12) most = std::max(most, whole[i]);
  EXPECT_GT(most, 0) << "the steps channel should count the rays' work";
  for (int ty = 0; ty < 48; ty += 16)
    for (int tx = 0; tx < 48; tx += 16) {
      const std::string name = "tile_" + std::to_string(tx) + "_" + std::to_string(ty) + ".exr";
      SCOPED_TRACE(name);
      ASSERT_EQ(run_softtrace(base + " --threads 1 --pixel-bounds " + std::to_string(tx) + "," +
                              std::to_string(tx + 16) + "," + std::to_string(ty) + "," +
                              std::to_string(ty + 16) + " -o " + dir + "/" + name)
                    .status,
                0);
      const std::vector<float> tile = pixels(dir + "/" + name);
      ASSERT_EQ(tile.size(), 16u * 16u * 12u);
      int differ = 0;
      for (int y = 0; y < 16; ++y)
        differ += std::memcmp(&tile[size_t(y) * 16 * 12], &whole[(size_t(ty + y) * 48 + tx) * 12],
                              16 * 12 * sizeof(float)) != 0;
      EXPECT_EQ(differ, 0) << "rows of the tile alone differ from the whole frame's";
    }
}

}  // namespace
}  // namespace softtrace::test

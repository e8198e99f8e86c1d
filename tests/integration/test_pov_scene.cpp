// tools/blob_scene.py --pov: the POV-Ray scene tools/pov_compare.py times against softtrace must
// be the same picture: the same spheres, threshold and camera, with softtrace's right-handed z-up
// (x, y, z) written as POV's left-handed y-up <x, z, y>, and POV's horizontal angle from
// softtrace's vertical fov.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "cli_util.h"

namespace softtrace::test {
namespace {

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::stod(item));
  return out;
}

TEST(PovScene, BlobSceneWritesTheSameSpheresAndCameraForPovRay) {
  const std::string dir = temp_dir("pov_scene");
  const RunResult gen =
      run_command("python3 " + source_path("tools/blob_scene.py") +
                  " 25 --width 40 --height 30 -o " + dir + "/b.json --pov " + dir + "/b.pov");
  ASSERT_EQ(gen.status, 0) << gen.err;
  const nlohmann::json scene = nlohmann::json::parse(read_file(dir + "/b.json"));
  const std::string pov = read_file(dir + "/b.pov");

  const auto& children = scene.at("objects").at(0).at("field").at("children");
  const std::regex sphere(R"(sphere \{ <([^>]*)>, ([^,]*), 1 \})");
  std::vector<std::smatch> spheres;
  for (auto it = std::sregex_iterator(pov.begin(), pov.end(), sphere); it != std::sregex_iterator();
       ++it)
    spheres.push_back(*it);
  ASSERT_EQ(spheres.size(), children.size());
  for (size_t i = 0; i < spheres.size(); ++i) {
    const auto c = children[i].at("translate").get<std::vector<double>>();
    const std::vector<double> p = numbers(spheres[i][1].str());
    ASSERT_EQ(p.size(), 3u);
    EXPECT_NEAR(p[0], c[0], 1e-6);
    EXPECT_NEAR(p[1], c[2], 1e-6) << "POV's y is softtrace's z";
    EXPECT_NEAR(p[2], c[1], 1e-6) << "POV's z is softtrace's y";
    EXPECT_NEAR(std::stod(spheres[i][2].str()),
                children[i].at("distance").at("radii").at(0).get<double>(), 1e-6);
  }
  EXPECT_NE(pov.find("blob { threshold 0.5"), std::string::npos) << pov.substr(0, 600);

  const auto& cam = scene.at("camera");
  const auto eye = cam.at("eye").get<std::vector<double>>();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(pov, m, std::regex(R"(location <([^>]*)>)")));
  const std::vector<double> loc = numbers(m[1].str());
  EXPECT_NEAR(loc[0], eye[0], 1e-9);
  EXPECT_NEAR(loc[1], eye[2], 1e-9);
  EXPECT_NEAR(loc[2], eye[1], 1e-9);
  ASSERT_TRUE(std::regex_search(pov, m, std::regex(R"(right x\*40/30 up y angle ([0-9.]+))")));
  const double vfov = cam.at("fov").get<double>() * M_PI / 180;
  EXPECT_NEAR(std::stod(m[1].str()), 2 * std::atan(std::tan(vfov / 2) * 40 / 30) * 180 / M_PI,
              1e-6);

  // And softtrace renders the JSON half.
  EXPECT_EQ(run_softtrace("render " + dir + "/b.json -o " + dir + "/b.png --quiet").status, 0);
}

}  // namespace
}  // namespace softtrace::test

// Scene loading: defaults, conventions, bounds and the region box, and located errors that need
// a scene around them (the bad-scene corpus covers the command line).
#include <gtest/gtest.h>

#include "scene.h"

namespace softtrace {
namespace {

const char* kBall = R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[2,2,2],"n":2}})";

Scene scene_with(const std::string& object) {
  return parse_scene(R"({"camera":{"eye":[10,0,0],"target":[0,0,0]},"objects":[)" + object + "]}",
                     "s.json");
}

TEST(SceneLoading, DefaultsFollowTheConvention) {
  const Scene s = scene_with(std::string(R"({"field":)") + kBall + "}");
  ASSERT_EQ(s.objects.size(), 1u);
  const SceneObject& o = s.objects[0];
  EXPECT_EQ(o.name, "object0");
  EXPECT_EQ(o.convention, Convention::Soft);
  EXPECT_EQ(o.iso, 0.5);
  EXPECT_EQ(o.inside_sign, 1);
  // The support of P(d) is {d < 1}: the box of half-side 2.
  EXPECT_NEAR(o.bounds.hi.x, 2, 1e-9);
  EXPECT_NEAR(o.bounds.lo.z, -2, 1e-9);
  EXPECT_EQ(s.image.width, 640);
  EXPECT_EQ(s.lights.size(), 2u) << "a key light and an ambient one by default";

  const Scene z = scene_with(
      R"({"convention":"zero","field":{"type":"offset","children":[{"type":"lp_metric","radii":[2,2,2],"n":2}]}})");
  EXPECT_EQ(z.objects[0].iso, 0);
  EXPECT_EQ(z.objects[0].inside_sign, -1);
  const Scene c = scene_with(
      R"({"convention":"constructive","iso":0.5,"field":{"type":"lp_metric","radii":[2,2,2],"n":2}})");
  EXPECT_EQ(c.objects[0].iso, 0.5);
  EXPECT_NEAR(c.objects[0].bounds.hi.y, 1, 1e-9) << "{d <= 0.5} for radius 2";
}

TEST(SceneLoading, GivenBoundsReplaceTheRegionBox) {
  const Scene s = scene_with(std::string(R"({"bounds":[[-1,-2,-3],[1,2,0.5]],"field":)") + kBall + "}");
  EXPECT_EQ(s.objects[0].bounds.lo.y, -2);
  EXPECT_EQ(s.objects[0].bounds.hi.z, 0.5);
  try {
    scene_with(std::string(R"({"bounds":[[1,-2,-3],[1,2,3]],"field":)") + kBall + "}");
    FAIL() << "an empty box must be rejected";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "s.json: /objects/0/bounds: expected each minimum below its maximum");
  }
  EXPECT_THROW(scene_with(std::string(R"({"bounds":[[1,2,3]],"field":)") + kBall + "}"),
               SceneError);
}

TEST(SceneLoading, DuplicateNamesAndUnknownLights) {
  try {
    scene_with(std::string(R"({"name":"a","field":)") + kBall + R"(},{"name":"a","field":)" +
               kBall + "}");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "s.json: /objects/1/name: duplicate object name 'a'");
  }
  try {
    parse_scene(R"({"camera":{"eye":[10,0,0],"target":[0,0,0]},"lights":[{"type":"spot"}],
                   "objects":[{"field":)" + std::string(kBall) + "}]}",
                "s.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: /lights/0/type: unknown light type 'spot'"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace softtrace

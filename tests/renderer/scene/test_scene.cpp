// Scene loading: defaults, conventions, bounds and the region box, and located errors that need
// a scene around them (the bad-scene corpus covers the command line).
#include <gtest/gtest.h>

#include <cmath>

#include "scene/json_location.h"
#include "scene/json_nesting.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

const char* kBall =
    R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[2,2,2],"n":2}})";

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

// The document is the scene's (a render process ends without freeing it): it lives as long as
// the scene, moved or not, and goes with it.
TEST(SceneLoading, TheDocumentLivesAsLongAsTheScene) {
  std::weak_ptr<const void> document;
  {
    Scene s = scene_with(std::string(R"({"field":)") + kBall + "}");
    document = s.document;
    ASSERT_FALSE(document.expired());
    const auto& doc = *static_cast<const nlohmann::json*>(s.document.get());
    EXPECT_EQ(doc.at("objects").at(0).at("field").at("distance").at("n"), 2);
    const Scene moved = std::move(s);
    s = scene_with(std::string(R"({"field":)") + kBall + "}");
    EXPECT_FALSE(document.expired()) << "the moved scene holds it";
  }
  EXPECT_TRUE(document.expired());
}

// A C++ string may hold a NUL that the file system would end the path at: "x.json\0junk" is
// refused rather than loaded as x.json. The pixel limit is the command line's and Python's.
TEST(SceneLoading, PathsWithNulAndThePixelLimit) {
  const std::string path = std::string(SOFTTRACE_SOURCE_DIR "/scenes/fig000_12b_soft_blend.json");
  EXPECT_NO_THROW(load_scene(path));
  try {
    load_scene(path + std::string("\0junk", 5));
    FAIL() << "a path with a NUL byte was loaded";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("a path with a NUL byte"), std::string::npos);
  }
  ImageSettings image;
  image.width = 16384;
  image.height = 4096;
  EXPECT_NO_THROW(check_pixel_count(image, "s.json"));
  image.height = 4097;
  EXPECT_THROW(check_pixel_count(image, "s.json"), SceneError);
}

TEST(SceneLoading, GivenBoundsReplaceTheRegionBox) {
  const Scene s =
      scene_with(std::string(R"({"bounds":[[-1,-2,-3],[1,2,0.5]],"field":)") + kBall + "}");
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
    parse_scene(R"({"camera":{"eye":[10,0,0],"target":[0,0,0]},"lights":[{"type":"cylinder"}],
                   "objects":[{"field":)" +
                    std::string(kBall) + "}]}",
                "s.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: /lights/0/type: unknown light type 'cylinder'"),
              std::string::npos);
  }
}

// Vectors are normalised by their largest component first: no length overflows or underflows.
TEST(SceneLoading, HugeAndTinyVectorsKeepTheirDirection) {
  const Scene s = parse_scene(R"({"camera":{"eye":[10,0,0],"target":[0,0,0],"up":[0,1e308,1e308]},
      "lights":[{"type":"directional","direction":[-1.5e308,0,1e308]},
                {"type":"directional","direction":[0,-5e-324,0]}],
      "objects":[{"field":)" + std::string(kBall) +
                                  "}]}",
                              "s.json");
  EXPECT_NEAR(s.camera.up.y, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(s.camera.up.z, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(s.lights[0].direction.x, -1.5 / std::sqrt(3.25), 1e-15);
  EXPECT_NEAR(s.lights[0].direction.z, 1 / std::sqrt(3.25), 1e-15);
  EXPECT_EQ(s.lights[1].direction.y, -1);
  // Without lights, the key light comes from the camera and up: finite for a huge up too.
  const Scene d = parse_scene(R"({"camera":{"eye":[10,0,0],"target":[0,0,0],"up":[0,0,1e308]},
      "objects":[{"field":)" + std::string(kBall) +
                                  "}]}",
                              "s.json");
  EXPECT_NEAR(length(d.lights[0].direction), 1, 1e-15);
}

TEST(SceneLoading, DistancesWhoseSquaresOverflowAreRefused) {
  const auto error = [](const std::string& camera, const std::string& lights) {
    try {
      parse_scene(R"({"camera":)" + camera + R"(,"lights":)" + lights + R"(,"objects":[{"field":)" +
                      kBall + "}]}",
                  "s.json");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string camera = R"({"eye":[10,0,0],"target":[0,0,0]})",
                    lights = R"([{"type":"ambient"}])";
  EXPECT_EQ(error(R"({"eye":[0,0,0],"target":[1e200,0,0]})", lights),
            "s.json: /camera/target: expected a target between 1e-150 and 1e150 from the eye");
  EXPECT_EQ(error(R"({"eye":[0,0,0],"target":[1e-200,0,0]})", lights),
            "s.json: /camera/target: expected a target between 1e-150 and 1e150 from the eye");
  EXPECT_EQ(error(camera, R"([{"type":"ambient"},{"type":"point","position":[0,-1e200,0]}])"),
            "s.json: /lights/1/position: expected a point light within 1e150 of the objects (one "
            "farther away is a directional light)");
  EXPECT_EQ(error(camera, R"([{"type":"point","position":[0,-1e149,0]}])"), "no error");
}

TEST(SceneText, LineBreaksAreLfCrLfOrALoneCr) {
  const std::string text = "a\nb\r\nc\rd\r\re";
  EXPECT_EQ(line_col(text, 0), "1:1");
  EXPECT_EQ(line_col(text, 2), "2:1");
  EXPECT_EQ(line_col(text, 3), "2:2") << "the CR of CR LF ends line 2, at its column 2";
  EXPECT_EQ(line_col(text, 5), "3:1");
  EXPECT_EQ(line_col(text, 7), "4:1");
  EXPECT_EQ(line_col(text, 9), "5:1") << "CR CR is two line breaks";
  EXPECT_EQ(line_col(text, 10), "6:1");
  EXPECT_EQ(line_col(text, 11), "6:2") << "the end of the input";
}

TEST(SceneText, KeysAreCountedOutsideStringsAndComments) {
  const std::string text =
      "{\"a\": \"x:y\", // \"no\": 1\r  /* \"no\": 2 */ \"b\" /* c */ : {\"c\\\"\":1}}";
  EXPECT_EQ(object_key_offset(text, 0), text.find("\"a\""));
  EXPECT_EQ(object_key_offset(text, 1), text.find("\"b\""));
  EXPECT_EQ(object_key_offset(text, 2), text.find("\"c\\"));
  EXPECT_EQ(object_key_offset(text, 3), std::string::npos);
}

// Every located error counts lines the same way, whatever the line endings.
TEST(SceneText, LocatedErrorsCountCrOnlyLines) {
  const auto error = [](const std::string& text) {
    try {
      parse_scene(text, "s.json");
    } catch (const SceneError& e) {
      return std::string(e.what()).substr(0, std::string(e.what()).find(": ", 7));
    }
    return std::string("no error");
  };
  for (const std::string eol : {"\n", "\r\n", "\r"}) {
    SCOPED_TRACE(testing::PrintToString(eol));
    EXPECT_EQ(error("//" + eol + "{" + eol + "  \"camera\": x}"), "s.json:3:13");
    EXPECT_EQ(error("//" + eol + eol + "  [1e400]"), "s.json:3:4");
    EXPECT_EQ(error("/*" + eol + "*/ {\"a\": 1," + eol + "\"a\": 2}"), "s.json:3:1");
    EXPECT_EQ(error("{" + eol + "\"c\"" + eol + "}"), "s.json:3:1");
    std::string deep = "//" + eol + " ";
    deep += std::string(kMaxJsonNesting + 1, '[');
    EXPECT_EQ(error(deep), "s.json:2:" + std::to_string(kMaxJsonNesting + 2));
  }
}

TEST(SceneText, DuplicateKeysAreComparedDecoded) {
  try {
    scene_with(std::string(R"({"field":)") + kBall + R"(, "n\u0061me": "a", "name": "b"})");
    FAIL() << "a duplicate key must be refused";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "s.json:1:161: duplicate key 'name'");
  }
  // The same key in different objects, or at different depths, is no duplicate.
  EXPECT_NO_THROW(scene_with(std::string(R"({"name":"a","field":)") + kBall +
                             R"(},{"name":"b","field":)" + kBall + "}"));
}

}  // namespace
}  // namespace softtrace

// The scene's file hash names tiles and frames (tiles.cpp, frame_metadata.cpp): it must be the
// published 64-bit FNV-1a, or two builds would name the same scene differently. Vectors from the
// FNV reference test suite (Fowler, Noll, Vo).
TEST(SceneHash, IsThePublishedFnv1a64) {
  EXPECT_EQ(softtrace::fnv1a(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(softtrace::fnv1a("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(softtrace::fnv1a("foobar"), 0x85944171f73967e8ULL);
  // Continuing from a hash is hashing the concatenation.
  EXPECT_EQ(softtrace::fnv1a("bar", softtrace::fnv1a("foo")), softtrace::fnv1a("foobar"));
}

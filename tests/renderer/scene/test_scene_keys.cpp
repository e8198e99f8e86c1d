// The scene's own keys (renderer/scene/scene_keys.cpp) against the loader and the documentation:
// the loader takes every listed key and reads no other (Params::check_keys), an unknown key is
// reported before a missing one in every scene object, and docs/scene-format.md's "The scene"
// has one table per list with exactly its keys, in its order.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "scene/scene.h"
#include "scene/scene_keys.h"

namespace softtrace {
namespace {

using json = nlohmann::json;

const char* kKeysBall =
    R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[2,2,2],"n":2}})";

// Between them, every key of every list, at the places `kWhere` names.
const std::string kEveryKeyCameras = std::string(R"({
  "camera": {"projection": "perspective", "eye": [10, 0, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 40,
             "aspect": 1.5, "aperture": 0.1, "focal_distance": 9, "blur_samples": 2},
  "image": {"width": 8, "height": 6, "spp": 2, "max_trace_level": 3,
            "antialias": {"threshold": 0.3, "depth": 2, "gamma": 2.2},
            "ambient_occlusion": {"samples": 4, "distance": 2}},
  "background": {"gradient": [[0.1, 0.2, 0.3], [0.4, 0.5, 0.9]], "up": [0, 0, 1]},
  "lights": [
    {"type": "directional", "direction": [-1, 0, 0], "intensity": 1, "color": [1, 1, 1], "shadows": false},
    {"type": "point", "position": [5, 5, 5], "intensity": 2, "color": [1, 0.5, 1], "shadows": true,
     "fade_distance": 3, "fade_power": 2,
     "area": {"axis1": [1, 0, 0], "axis2": [0, 1, 0], "size1": 3, "size2": 2, "adaptive": 1, "jitter": true}},
    {"type": "ambient", "intensity": 0.1, "color": [1, 1, 1]},
    {"type": "spot", "position": [0, 0, 9], "point_at": [0, 0, 0], "radius": 10, "falloff": 20,
     "tightness": 5, "intensity": 1, "color": [1, 1, 1], "shadows": true, "fade_distance": 9,
     "fade_power": 1, "area": {"axis1": [1, 0, 0], "axis2": [0, 1, 0], "size1": 2, "size2": 2}}],
  "objects": [{"name": "ball", "material": {"color": [1, 0, 0], "ambient": 0.1, "diffuse": 0.6,
               "brilliance": 2, "phong": 0.5, "phong_size": 60, "specular": 0.3, "roughness": 0.02,
               "metallic": 0.5, "reflection": [0.1, 0.2, 0.3], "fresnel": true,
               "reflection_min": 0.05, "conserve_energy": true, "filter": 0.1, "transmit": 0.2,
               "ior": 1.3}, "convention": "soft", "iso": 0.4,
               "bounds": [[-3, -3, -3], [3, 3, 3]], "field": )") +
                                     kKeysBall +
                                     R"(},
    {"name": "floor", "material": {"color": [1, 1, 1]}, "shape": {"type": "plane", "normal": [0, 0, 1],
     "distance": -3, "scale": [1, 1, 1], "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 0],
     "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}},
    {"shape": {"type": "box", "corner1": [0, 0, 0], "corner2": [1, 1, 1], "scale": [1, 2, 1],
     "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 1], "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}},
    {"shape": {"type": "sphere", "center": [0, 0, 0], "radius": 1, "scale": [1, 2, 1],
     "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 1], "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}},
    {"shape": {"type": "cylinder", "base": [0, 0, 0], "cap": [0, 0, 1], "radius": 1, "scale": [1, 2, 1],
     "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 1], "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}},
    {"shape": {"type": "cone", "base": [0, 0, 0], "base_radius": 1, "cap": [0, 0, 1], "cap_radius": 0.5,
     "scale": [1, 2, 1], "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 1],
     "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}},
    {"shape": {"type": "disc", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 1, "hole_radius": 0.5,
     "scale": [1, 2, 1], "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 1],
     "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}},
    {"name": "cut", "material": {"color": [1, 1, 1]}, "csg": "difference", "cutaway_textures": true,
     "scale": [1, 1, 1],
     "rotate": {"axis": [0, 0, 1], "deg": 5}, "translate": [0, 0, 1],
     "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]], "operands": [
     {"shape": {"type": "sphere", "center": [0, 0, 0], "radius": 2}},
     {"shape": {"type": "box", "corner1": [0, 0, 0], "corner2": [3, 3, 3]}}]},
    {"name": "triangle", "mesh": ")" SOFTTRACE_SOURCE_DIR
                                     R"(/tests/bad_scenes/meshes/triangle.obj"}],
  "animation": {"frames": 1, "cameras": [{"eye": [0, 10, 0], "target": [0, 0, 0]}]}
})";
const std::string kEveryKeyTurntable =
    std::string(R"({"camera": {"eye": [10, 0, 0], "target": [0, 0, 0]}, "objects": [{"field": )") +
    kKeysBall +
    R"(}], "animation": {"frames": 4, "turntable": {"axis": [0, 0, 1], "degrees": 90}}})";

// Where each list's object sits in the two scenes above.
const std::map<std::string, std::vector<std::string>> kWhere = {
    {"top level", {""}},
    {"camera", {"/camera", "/animation/cameras/0"}},
    {"image", {"/image"}},
    {"antialias", {"/image/antialias"}},
    {"ambient_occlusion", {"/image/ambient_occlusion"}},
    {"background", {"/background"}},
    {"light: directional", {"/lights/0"}},
    {"light: point", {"/lights/1"}},
    {"light: ambient", {"/lights/2"}},
    {"light: spot", {"/lights/3"}},
    {"area light", {"/lights/1/area", "/lights/3/area"}},
    {"object", {"/objects/0", "/objects/1", "/objects/7", "/objects/8"}},
    {"material", {"/objects/0/material"}},
    {"shape: plane", {"/objects/1/shape"}},
    {"shape: box", {"/objects/2/shape"}},
    {"shape: sphere", {"/objects/3/shape"}},
    {"shape: cylinder", {"/objects/4/shape"}},
    {"shape: cone", {"/objects/5/shape"}},
    {"shape: disc", {"/objects/6/shape"}},
    {"animation", {"/animation"}},
    {"turntable", {"/animation/turntable"}},
};

TEST(SceneKeys, TheLoaderTakesEveryListedKeyAndReadsNoOther) {
  // Loading succeeds: every key present was read (finish() refuses unread keys), and check_keys
  // made reading any key outside its list a std::logic_error.
  EXPECT_NO_THROW(parse_scene(kEveryKeyCameras, "cameras.json"));
  EXPECT_NO_THROW(parse_scene(kEveryKeyTurntable, "turntable.json"));
  const json docs[] = {json::parse(kEveryKeyCameras), json::parse(kEveryKeyTurntable)};
  ASSERT_EQ(kWhere.size(), scene_key_lists().size()) << "a list with no place in the test scenes";
  for (const SceneKeyList& list : scene_key_lists()) {
    ASSERT_TRUE(kWhere.count(list.name)) << list.name;
    std::set<std::string> present;
    for (const json& doc : docs)
      for (const std::string& at : kWhere.at(list.name)) {
        const json::json_pointer pointer(at);
        if (!doc.contains(pointer)) continue;
        for (auto it = doc.at(pointer).begin(); it != doc.at(pointer).end(); ++it)
          present.insert(it.key());
      }
    EXPECT_EQ(present, std::set<std::string>(list.keys.begin(), list.keys.end()))
        << "the test scenes should use exactly the keys of '" << list.name << "'";
  }
}

TEST(SceneKeys, ReadingAKeyOutsideTheListIsALoaderBug) {
  const json j = json::parse(R"({"a": 1})");
  const Params p(j, "", std::make_shared<const std::string>("t.json"));
  p.check_keys({"a", "b"});
  EXPECT_FALSE(p.has("b"));
  EXPECT_THROW(p.has("c"), std::logic_error);
  EXPECT_THROW(p.number("c", 0), std::logic_error);
}

std::string load_error(const std::string& text) {
  try {
    parse_scene(text, "s.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(loaded)";
}

// In every scene object, a misspelled key beside a missing required one names the misspelling.
TEST(SceneKeys, UnknownKeysAreReportedBeforeMissingOnes) {
  const std::string camera = R"("camera": {"eye": [10, 0, 0], "target": [0, 0, 0]})";
  const std::string objects = std::string(R"("objects": [{"field": )") + kKeysBall + "}]";
  const struct {
    std::string scene, expected;
  } cases[] = {
      {"{" + camera + R"(, "objcts": []})",
       "s.json: /objcts: unknown key 'objcts' (did you mean 'objects'?)"},
      {R"({"camra": {}, )" + objects + "}",
       "s.json: /camra: unknown key 'camra' (did you mean 'camera'?)"},
      {R"({"camera": {"eye": [10, 0, 0], "trget": [0, 0, 0]}, )" + objects + "}",
       "s.json: /camera/trget: unknown key 'trget' (did you mean 'target'?)"},
      {"{" + camera + R"(, "image": {"widht": 4}, )" + objects + "}",
       "s.json: /image/widht: unknown key 'widht' (did you mean 'width'?)"},
      {"{" + camera + R"(, "lights": [{"tpye": "point"}], )" + objects + "}",
       "s.json: /lights/0/tpye: unknown key 'tpye' (did you mean 'type'?)"},
      {"{" + camera + R"(, "lights": [{"type": "point", "positon": [1, 2, 3]}], )" + objects + "}",
       "s.json: /lights/0/positon: unknown key 'positon' (did you mean 'position'?)"},
      {"{" + camera + R"(, "lights": [{"type": "directional", "position": [1, 2, 3]}], )" +
           objects + "}",
       "s.json: /lights/0/position: unknown key 'position' for a directional light"},
      {"{" + camera + R"(, "lights": [{"type": "ambient", "shadows": false}], )" + objects + "}",
       "s.json: /lights/0/shadows: unknown key 'shadows' for an ambient light"},
      {"{" + camera + R"(, "objects": [{"feild": {}}]})",
       "s.json: /objects/0/feild: unknown key 'feild' (did you mean 'field'?)"},
      {"{" + camera + R"(, "objects": [{"material": {"colour": [1, 1, 1]}, "field": )" + kKeysBall +
           "}]}",
       "s.json: /objects/0/material/colour: unknown key 'colour' (did you mean 'color'?)"},
      {"{" + camera + ", " + objects + R"(, "animation": {"frmes": 3, "turntable": {}}})",
       "s.json: /animation/frmes: unknown key 'frmes' (did you mean 'frames'?)"},
      {"{" + camera + ", " + objects + R"(, "animation": {"frames": 3, "turntable": {"axsi": 1}}})",
       "s.json: /animation/turntable/axsi: unknown key 'axsi' (did you mean 'axis'?)"},
      {"{" + camera + ", " + objects +
           R"(, "animation": {"cameras": [{"eye": [1, 0, 0], "taget": [0, 0, 0]}]}})",
       "s.json: /animation/cameras/0/taget: unknown key 'taget' (did you mean 'target'?)"},
  };
  for (const auto& c : cases) EXPECT_EQ(load_error(c.scene), c.expected) << c.scene;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SceneChapter {
  std::map<std::string, std::vector<std::string>> keys;  // "### <list>" -> its table's keys
  std::vector<std::string> examples;                     // its ```json blocks: whole scenes
};

// docs/scene-format.md's "## The scene": the "### <list>" sections with the keys of their table
// rows ("| `key` | ..."), in order, and the chapter's ```json examples.
SceneChapter scene_chapter(const std::string& text) {
  SceneChapter chapter;
  auto& doc = chapter.keys;
  std::stringstream in(text);
  std::string line;
  bool in_chapter = false, in_example = false;
  std::vector<std::string>* current = nullptr;
  while (std::getline(in, line)) {
    if (in_example) {
      if (line.rfind("```", 0) == 0)
        in_example = false;
      else
        chapter.examples.back() += line + "\n";
    } else if (in_chapter && line.rfind("```json", 0) == 0) {
      in_example = true;
      chapter.examples.emplace_back();
    } else if (line.rfind("## ", 0) == 0) {
      in_chapter = line == "## The scene";
      current = nullptr;
    } else if (in_chapter && line.rfind("### ", 0) == 0) {
      const std::string name = line.substr(4);
      EXPECT_FALSE(doc.count(name)) << "documented twice: " << name;
      current = &doc[name];
    } else if (current && line.rfind("| `", 0) == 0) {
      current->push_back(line.substr(3, line.find('`', 3) - 3));
    }
  }
  return chapter;
}

TEST(SceneKeys, SceneFormatDocHasOneTablePerListWithExactlyItsKeys) {
  const std::string path = std::string(SOFTTRACE_SOURCE_DIR) + "/docs/scene-format.md";
  const SceneChapter chapter = scene_chapter(read_text(path));
  const auto& doc = chapter.keys;
  ASSERT_FALSE(doc.empty()) << path << " has no \"## The scene\" with \"### \" sections";
  for (const SceneKeyList& list : scene_key_lists()) {
    const auto it = doc.find(list.name);
    if (it == doc.end()) {
      ADD_FAILURE() << path << " has no section \"### " << list.name << "\" under \"## The scene\"";
      continue;
    }
    EXPECT_EQ(it->second, list.keys)
        << path << ": \"### " << list.name << "\" documents other keys than the loader's list";
  }
  for (const auto& [name, keys] : doc) {
    bool listed = false;
    for (const SceneKeyList& list : scene_key_lists()) listed = listed || list.name == name;
    EXPECT_TRUE(listed) << path << ": \"### " << name << "\" is no list of the loader";
  }
  ASSERT_FALSE(chapter.examples.empty()) << path << ": \"## The scene\" has no ```json example";
  for (const std::string& example : chapter.examples) {
    try {
      parse_scene(example, "example.json");
    } catch (const SceneError& e) {
      ADD_FAILURE() << path << ": an example of \"## The scene\" does not load: " << e.what();
    }
  }
}

}  // namespace
}  // namespace softtrace

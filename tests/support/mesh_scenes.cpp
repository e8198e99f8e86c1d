#include "mesh_scenes.h"

#include "scene_files.h"
#include "tracer_scenes.h"

namespace softtrace::mesh_scenes {

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  auto add = [&](const std::string& name, Scene s) {
    auto scene = std::make_shared<Scene>(std::move(s));
    for (size_t i = 0; i < scene->objects.size(); ++i)
      if (scene->objects[i].field)  // a plain primitive or a CSG has no field to mesh
        cases.push_back({name + "#" + std::to_string(i), scene, int(i)});
  };
  for (const auto& f : test::scene_files()) add(f.filename().string(), load_scene(f.string()));
  for (int i = 0; i < tracer_scenes::kCount; ++i)
    add("tracer_" + std::to_string(i), parse_scene(tracer_scenes::kScenes[i], "tracer"));
  return cases;
}

std::string test_name(const Case& c) {
  std::string s = c.name;
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

}  // namespace softtrace::mesh_scenes

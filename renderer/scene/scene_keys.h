// The keys of the scene's own objects: the top level, camera, image, lights, objects, material,
// animation (the field nodes' keys are in fieldlib/kinds.cpp). The loader declares each object's
// list before it reads anything (Params::check_keys), so a misspelled key is reported before a
// missing one and the loader cannot read a key the list lacks; docs/scene-format.md's "The
// scene" has one table per list, and tests/renderer/scene/test_scene_keys.cpp holds the three
// together.
#pragma once

#include <string>
#include <vector>

namespace softtrace {

struct SceneKeyList {
  std::string name;               // as docs/scene-format.md's heading: "camera", "light: point"
  std::vector<std::string> keys;  // in the documentation's order
};

// Every list, in the documentation's order.
const std::vector<SceneKeyList>& scene_key_lists();

// The list called `name`; std::logic_error for a name that is none.
const std::vector<std::string>& scene_keys(const std::string& name);

}  // namespace softtrace

// The example scenes the scene-wide tests run over: scenes/*.json of the source tree, sorted, so
// that cases keep their order and names on every machine (scenes/meshes/ holds the mesh scene's
// OBJ files, not scenes). Needs SOFTTRACE_SOURCE_DIR, which every test target defines.
#pragma once

#include <algorithm>
#include <filesystem>
#include <vector>

namespace softtrace::test {

inline std::vector<std::filesystem::path> scene_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(SOFTTRACE_SOURCE_DIR "/scenes"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace softtrace::test

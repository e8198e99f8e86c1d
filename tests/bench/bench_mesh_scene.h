// The mesh benchmarks' scene: the 1000-blob cloud of tools/blob_scene.py, written once per run.
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "scene/scene.h"

namespace softtrace {

inline const Scene& mesh_bench_blobs() {
  static const Scene scene = [] {
    const std::string path = "/tmp/softtrace_mesh_bench_blobs1000.json";
    const std::string cmd = "python3 " SOFTTRACE_SOURCE_DIR "/tools/blob_scene.py 1000 -o " + path;
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("tools/blob_scene.py failed");
    return load_scene(path);
  }();
  return scene;
}

}  // namespace softtrace

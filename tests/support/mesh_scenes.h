// The scenes the mesh tests run over: every file in scenes/ and the tracer tests' stress scenes,
// each object of each as one case.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace softtrace::mesh_scenes {

struct Case {
  std::string name;              // "file.json#object" or "tracer_N#object"
  std::shared_ptr<Scene> scene;  // owns the object
  int object = 0;
};

std::vector<Case> all_cases();
// A gtest-safe version of the case's name.
std::string test_name(const Case& c);
// How gtest prints a case (its name, not its bytes).
inline void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

}  // namespace softtrace::mesh_scenes

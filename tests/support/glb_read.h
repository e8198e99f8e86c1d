// A GLB (glTF 2.0 binary) reader for the tests, written from the specification: the one mesh
// softtrace writes, back in softtrace's z-up frame. Independent of the writer's code.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "math/vec.h"

namespace softtrace::glb {

struct Glb {
  std::vector<Vec3> positions, normals, colors;  // positions and normals back to z up
  std::vector<uint32_t> indices;
  int index_type = 0;  // 5123 (16-bit) or 5125 (32-bit)
};

// Reads `path`, checking the header, the chunks and the version with gtest expectations.
Glb read(const std::string& path);

}  // namespace softtrace::glb

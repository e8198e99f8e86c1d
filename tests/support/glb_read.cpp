#include "glb_read.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace softtrace::glb {
namespace {

template <class T>
T at(const std::string& bytes, size_t offset) {
  T v{};
  EXPECT_LE(offset + sizeof v, bytes.size());
  if (offset + sizeof v <= bytes.size()) std::memcpy(&v, bytes.data() + offset, sizeof v);
  return v;
}

}  // namespace

Glb read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  const std::string b = s.str();
  Glb g;
  EXPECT_EQ(at<uint32_t>(b, 0), 0x46546C67u);
  EXPECT_EQ(at<uint32_t>(b, 4), 2u);
  EXPECT_EQ(at<uint32_t>(b, 8), b.size());
  const uint32_t json_size = at<uint32_t>(b, 12);
  EXPECT_EQ(json_size % 4, 0u);
  EXPECT_EQ(at<uint32_t>(b, 16), 0x4E4F534Au);
  const auto doc = nlohmann::json::parse(b.substr(20, json_size));
  const size_t bin = 20 + json_size + 8;
  EXPECT_EQ(at<uint32_t>(b, bin - 4), 0x004E4942u);
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  const auto& prim = doc["meshes"][0]["primitives"][0];
  auto view_of = [&](int accessor) {
    const auto& a = doc["accessors"][accessor];
    const auto& v = doc["bufferViews"][a["bufferView"].get<int>()];
    return std::make_pair(a, bin + v["byteOffset"].get<size_t>());
  };
  auto vectors = [&](const char* name, bool frame) {
    const auto [a, offset] = view_of(prim["attributes"][name].get<int>());
    std::vector<Vec3> out;
    for (size_t i = 0; i < a["count"].get<size_t>(); ++i) {
      const Vec3 v{at<float>(b, offset + 12 * i), at<float>(b, offset + 12 * i + 4),
                   at<float>(b, offset + 12 * i + 8)};
      out.push_back(frame ? Vec3{v.x, -v.z, v.y} : v);  // glTF's y up back to z up
    }
    return out;
  };
  g.positions = vectors("POSITION", true);
  g.normals = vectors("NORMAL", true);
  g.colors = vectors("COLOR_0", false);
  const auto [a, offset] = view_of(prim["indices"].get<int>());
  g.index_type = a["componentType"];
  for (size_t i = 0; i < a["count"].get<size_t>(); ++i)
    g.indices.push_back(g.index_type == 5125 ? at<uint32_t>(b, offset + 4 * i)
                                             : at<uint16_t>(b, offset + 2 * i));
  return g;
}

}  // namespace softtrace::glb

// glTF 2.0 binary (GLB): a 12-byte header, a JSON chunk and a BIN chunk, each padded to 4 bytes
// (JSON with spaces, BIN with zeros). The BIN chunk holds positions, normals, colours (float
// VEC3 each) and the indices, 16-bit while every index fits (65,535 vertices), 32-bit past that.
// Softtrace's z-up frame becomes glTF's y-up one by (x, y, z) -> (x, z, -y).
#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "io/mesh_bytes.h"
#include "io/mesh_file.h"

namespace softtrace {
namespace {

Vec3 y_up(const Vec3& v) {
  return {v.x, v.z, -v.y};
}

}  // namespace

void write_glb(std::FILE* out, const Mesh& m) {
  using namespace mesh_bytes;
  using nlohmann::json;
  const size_t nv = m.vertices.size(), nf = m.faces.size();
  const bool wide = nv > 65535;
  const size_t index_size = wide ? 4 : 2;
  const size_t attrib = nv * 12, indices = nf * 3 * index_size;
  const size_t index_padded = (indices + 3) / 4 * 4;
  const size_t bin_size = 3 * attrib + index_padded;
  if (bin_size > std::numeric_limits<uint32_t>::max() - (1u << 20))
    throw std::runtime_error("the mesh is too large for one GLB file (4 GiB)");

  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Vec3& v : m.vertices)
    for (int a = 0; a < 3; ++a) {
      const double c = float(y_up(v)[a]);
      lo[a] = std::min(lo[a], c);
      hi[a] = std::max(hi[a], c);
    }
  json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "softtrace mesh"}};
  doc["scene"] = 0;
  doc["scenes"] = json::array({{{"nodes", {0}}}});
  doc["nodes"] = json::array({{{"mesh", 0}}});
  json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"COLOR_0", 2}}},
                    {"indices", 3},
                    {"mode", 4},
                    {"material", 0}};
  doc["meshes"] = json::array({{{"primitives", {primitive}}}});
  doc["materials"] = json::array(
      {{{"pbrMetallicRoughness",
         {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}},
        {"doubleSided", false}}});
  doc["buffers"] = json::array({{{"byteLength", bin_size}}});
  json views = json::array();
  for (int i = 0; i < 3; ++i)
    views.push_back(
        {{"buffer", 0}, {"byteOffset", i * attrib}, {"byteLength", attrib}, {"target", 34962}});
  views.push_back(
      {{"buffer", 0}, {"byteOffset", 3 * attrib}, {"byteLength", indices}, {"target", 34963}});
  doc["bufferViews"] = views;
  json accessors = json::array();
  const bool empty = nv == 0;
  accessors.push_back({{"bufferView", 0},
                       {"componentType", 5126},
                       {"count", nv},
                       {"type", "VEC3"},
                       {"min", empty ? json::array({0, 0, 0}) : json::array({lo.x, lo.y, lo.z})},
                       {"max", empty ? json::array({0, 0, 0}) : json::array({hi.x, hi.y, hi.z})}});
  accessors.push_back(
      {{"bufferView", 1}, {"componentType", 5126}, {"count", nv}, {"type", "VEC3"}});
  accessors.push_back(
      {{"bufferView", 2}, {"componentType", 5126}, {"count", nv}, {"type", "VEC3"}});
  accessors.push_back({{"bufferView", 3},
                       {"componentType", wide ? 5125 : 5123},
                       {"count", nf * 3},
                       {"type", "SCALAR"}});
  doc["accessors"] = accessors;

  std::string text = doc.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  const size_t total = 12 + 8 + text.size() + 8 + bin_size;
  put_value(out, uint32_t(0x46546C67));  // "glTF"
  put_value(out, uint32_t(2));
  put_value(out, uint32_t(total));
  put_value(out, uint32_t(text.size()));
  put_value(out, uint32_t(0x4E4F534A));  // "JSON"
  put(out, text.data(), text.size());
  put_value(out, uint32_t(bin_size));
  put_value(out, uint32_t(0x004E4942));  // "BIN\0"

  std::vector<float> buffer;
  buffer.reserve(std::min<size_t>(nv, 1 << 16) * 3);
  auto flush_vectors = [&](const MeshArray<Vec3>& vs, bool rotate) {
    for (size_t first = 0; first < vs.size(); first += 1 << 16) {
      buffer.clear();
      for (size_t i = first; i < std::min(vs.size(), first + (1 << 16)); ++i) {
        const Vec3 v = rotate ? y_up(vs[i]) : vs[i];
        buffer.insert(buffer.end(), {float(v.x), float(v.y), float(v.z)});
      }
      put(out, buffer.data(), buffer.size() * sizeof(float));
    }
  };
  flush_vectors(m.vertices, true);
  flush_vectors(m.normals, true);
  flush_vectors(m.colors, false);
  for (const auto& f : m.faces) {
    if (wide) {
      put(out, f.data(), 12);
    } else {
      const uint16_t s[3] = {uint16_t(f[0]), uint16_t(f[1]), uint16_t(f[2])};
      put(out, s, 6);
    }
  }
  const char zeros[4] = {};
  put(out, zeros, index_padded - indices);
}

}  // namespace softtrace

// The mesh files read back by readers written here from the formats' specifications (binary
// STL, OBJ, binary little-endian PLY, glTF 2.0 GLB), and written all or nothing.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_util.h"
#include "glb_read.h"
#include "io/mesh_file.h"
#include "mesh_scenes.h"
#include "model/program_builder.h"

namespace softtrace {
namespace {

namespace fs = std::filesystem;

template <class T>
T at(const std::string& bytes, size_t offset) {
  T v;
  EXPECT_LE(offset + sizeof v, bytes.size());
  std::memcpy(&v, bytes.data() + offset, sizeof v);
  return v;
}

std::string tmp(const std::string& name) {
  fs::create_directories(SOFTTRACE_TEST_TMP);
  return std::string(SOFTTRACE_TEST_TMP) + "/" + name;
}

// A meshed scene: fig. 12(b) at a coarse lattice.
const Mesh& sample() {
  static const Mesh m = [] {
    for (const auto& c : mesh_scenes::all_cases())
      if (c.name == "fig000_12b_soft_blend.json#0") {
        const SceneObject& o = c.scene->objects[0];
        const Program p = compile(*o.field);
        MeshOptions opt;
        opt.cells = 24;
        opt.color = {0.2, 0.5, 1.0};
        return mesh({&p, o.iso, o.inside_sign}, o.bounds, opt);
      }
    throw std::logic_error("no fig12b scene");
  }();
  return m;
}

void expect_near(const Vec3& a, const Vec3& b, double tol) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tol * (1 + std::abs(b[k])));
}

TEST(MeshFiles, BinaryStlHoldsEveryFaceWithItsNormal) {
  const Mesh& m = sample();
  ASSERT_GT(m.faces.size(), 100u);
  write_mesh(tmp("m.stl"), m);
  const std::string b = test::read_file(tmp("m.stl"));
  ASSERT_EQ(at<uint32_t>(b, 80), m.faces.size());
  ASSERT_EQ(b.size(), 84 + 50 * m.faces.size());
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const size_t o = 84 + 50 * f;
    Vec3 v[4];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) v[i][k] = at<float>(b, o + 12 * i + 4 * k);
    for (int i = 0; i < 3; ++i) expect_near(v[i + 1], m.vertices[m.faces[f][i]], 1e-6);
    EXPECT_NEAR(length(v[0]), 1, 1e-6);
    EXPECT_GT(dot(v[0], cross(v[2] - v[1], v[3] - v[1])), 0);
  }
}

TEST(MeshFiles, ObjSharesVerticesAndNormals) {
  const Mesh& m = sample();
  write_mesh(tmp("m.obj"), m);
  std::ifstream in(tmp("m.obj"));
  std::vector<Vec3> v, n;
  MeshArray<std::array<uint32_t, 3>> faces;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v" || tag == "vn") {
      Vec3 p;
      ls >> p.x >> p.y >> p.z;
      (tag == "v" ? v : n).push_back(p);
    } else if (tag == "f") {
      std::array<uint32_t, 3> f;
      for (auto& i : f) {
        std::string word;
        ls >> word;
        const size_t slash = word.find("//");
        ASSERT_NE(slash, std::string::npos);
        i = uint32_t(std::stoul(word.substr(0, slash)) - 1);
        EXPECT_EQ(word.substr(slash + 2), word.substr(0, slash));
      }
      faces.push_back(f);
    }
  }
  ASSERT_EQ(v.size(), m.vertices.size());
  ASSERT_EQ(n.size(), m.vertices.size());
  EXPECT_EQ(faces, m.faces);
  for (size_t i = 0; i < v.size(); ++i) {
    expect_near(v[i], m.vertices[i], 1e-8);
    expect_near(n[i], m.normals[i], 1e-6);
  }
}

TEST(MeshFiles, BinaryPlyHoldsNormalsAndColours) {
  const Mesh& m = sample();
  write_mesh(tmp("m.ply"), m);
  const std::string b = test::read_file(tmp("m.ply"));
  const size_t end = b.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = b.substr(0, end);
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(header.find("element vertex " + std::to_string(m.vertices.size()) + "\n"),
            std::string::npos);
  EXPECT_NE(header.find("element face " + std::to_string(m.faces.size()) + "\n"),
            std::string::npos);
  size_t o = end + 11;
  ASSERT_EQ(b.size(), o + 27 * m.vertices.size() + 13 * m.faces.size());
  for (size_t i = 0; i < m.vertices.size(); ++i, o += 27) {
    expect_near({at<float>(b, o), at<float>(b, o + 4), at<float>(b, o + 8)}, m.vertices[i], 1e-6);
    expect_near({at<float>(b, o + 12), at<float>(b, o + 16), at<float>(b, o + 20)}, m.normals[i],
                1e-6);
    // 0.2, 0.5, 1.0 linear are 124, 188, 255 in 8-bit sRGB.
    EXPECT_EQ(uint8_t(b[o + 24]), 124);
    EXPECT_EQ(uint8_t(b[o + 25]), 188);
    EXPECT_EQ(uint8_t(b[o + 26]), 255);
  }
  for (size_t f = 0; f < m.faces.size(); ++f, o += 13) {
    ASSERT_EQ(b[o], 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(at<int32_t>(b, o + 1 + 4 * k), int32_t(m.faces[f][k]));
  }
}

TEST(MeshFiles, GlbIsYUpWithSixteenBitIndicesWhenTheyFit) {
  const Mesh& m = sample();
  ASSERT_LE(m.vertices.size(), 65535u);
  write_mesh(tmp("m.glb"), m);
  const glb::Glb g = glb::read(tmp("m.glb"));
  EXPECT_EQ(g.index_type, 5123);
  ASSERT_EQ(g.positions.size(), m.vertices.size());
  ASSERT_EQ(g.indices.size(), 3 * m.faces.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    expect_near(g.positions[i], m.vertices[i], 1e-6);
    expect_near(g.normals[i], m.normals[i], 1e-6);
    expect_near(g.colors[i], m.colors[i], 1e-7);
  }
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(g.indices[3 * f + k], m.faces[f][k]);
}

TEST(MeshFiles, GlbIndicesAre32BitPast65535Vertices) {
  Mesh m;  // a strip of 70,000 vertices
  for (int i = 0; i < 70000; ++i) {
    m.vertices.push_back({double(i / 2), double(i % 2), 0});
    m.normals.push_back({0, 0, 1});
    m.colors.push_back({1, 1, 1});
  }
  for (uint32_t i = 0; i + 2 < 70000; i += 2) {
    m.faces.push_back({i, i + 2, i + 1});
    m.faces.push_back({i + 1, i + 2, i + 3});
  }
  write_mesh(tmp("wide.glb"), m);
  const glb::Glb g = glb::read(tmp("wide.glb"));
  EXPECT_EQ(g.index_type, 5125);
  ASSERT_EQ(g.indices.size(), 3 * m.faces.size());
  EXPECT_EQ(g.indices[g.indices.size() - 1], 69999u);
}

TEST(MeshFiles, AFailedWriteLeavesTheOldFile) {
  const std::string path = tmp("keep.obj");
  { std::ofstream(path) << "old\n"; }
  Mesh bad = sample();
  bad.faces.push_back({0, 1, uint32_t(bad.vertices.size())});
  EXPECT_THROW(write_mesh(path, bad), std::invalid_argument);
  EXPECT_EQ(test::read_file(path), "old\n");
  EXPECT_THROW(write_mesh(tmp("m.fbx"), sample()), std::invalid_argument);
  for (const auto& e : fs::directory_iterator(SOFTTRACE_TEST_TMP))
    EXPECT_NE(e.path().filename().string().rfind(".keep.obj.", 0), 0u) << "temporary file left";
}

}  // namespace
}  // namespace softtrace

namespace softtrace {
namespace {

int run(const std::string& args) {
  const int status =
      std::system((std::string(SOFTTRACE_BIN) + " mesh " + args + " 2>/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(MeshCli, WritesTheFileOrExitsTwoWritingNothing) {
  const std::string scene = SOFTTRACE_SOURCE_DIR "/scenes/fig000_12b_soft_blend.json";
  const std::string out = tmp("cli.obj");
  fs::remove(out);
  EXPECT_EQ(run(scene + " -o " + tmp("cli.fbx")), 2);
  EXPECT_EQ(run(scene + " -o " + out + " --bounds 1,2,3"), 2);
  EXPECT_EQ(run(scene + " -o " + out + " --bounds 0,1,0,1,1,0"), 2);
  EXPECT_EQ(run(scene + " -o " + out + " --object nope"), 2);
  EXPECT_EQ(run(scene + " -o " + out + " --voxel 1e-9"), 2);
  EXPECT_EQ(run(scene + " -o " + out + " --bounds 100,101,0,1,0,1"), 2);  // no surface there
  EXPECT_EQ(run(SOFTTRACE_SOURCE_DIR "/README.md -o " + out), 2);
  EXPECT_FALSE(fs::exists(out));
  ASSERT_EQ(run(scene + " -o " + out + " --cells 16 --threads 2 -q"), 0);
  EXPECT_EQ(test::read_file(out).rfind("# softtrace mesh: ", 0), 0u);
}

// scenes/molecule_two_colour.json: a red oxygen (centre (0, 0, 1.8), radius 2.6) and two white
// hydrogens that take the object's colour. The vertex on top of the oxygen lies outside both
// hydrogens' supports, the one at the far left outside the oxygen's, so each takes its atom's
// colour alone; the necks between them mix (POV-Ray's blob texture weights).
TEST(MeshCli, ComponentMaterialsColourTheVertices) {
  const std::string out = tmp("molecule.glb");
  fs::remove(out);
  ASSERT_EQ(run(SOFTTRACE_SOURCE_DIR "/scenes/molecule_two_colour.json -o " + out +
                " --cells 48 --threads 2 -q"),
            0);
  const glb::Glb g = glb::read(out);
  ASSERT_EQ(g.colors.size(), g.positions.size());
  ASSERT_FALSE(g.positions.empty());
  size_t top = 0, left = 0;
  for (size_t v = 0; v < g.positions.size(); ++v) {
    if (g.positions[v].z > g.positions[top].z) top = v;
    if (g.positions[v].x < g.positions[left].x) left = v;
  }
  const Vec3 red{0.8, 0.06, 0.04}, white{0.85, 0.85, 0.85};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(g.colors[top][k], red[k], 1e-6) << "top vertex " << k;
    EXPECT_NEAR(g.colors[left][k], white[k], 1e-6) << "left vertex " << k;
  }
  // Between the atoms: some vertices are neither colour alone, but mixes of the two.
  size_t mixed = 0;
  for (const Vec3& c : g.colors) {
    // A mix t red + (1 - t) white keeps g == b and lies strictly between them.
    const double t = (c.y - white.y) / (red.y - white.y);
    if (t > 0.05 && t < 0.95) {
      ++mixed;
      EXPECT_NEAR(c.x, t * red.x + (1 - t) * white.x, 1e-5);
      EXPECT_NEAR(c.z, t * red.z + (1 - t) * white.z, 1e-5);
    }
  }
  EXPECT_GT(mixed, 0u);
}

}  // namespace
}  // namespace softtrace

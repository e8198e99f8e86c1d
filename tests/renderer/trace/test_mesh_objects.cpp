// Triangle mesh objects (scene/triangle_mesh.h, io/mesh_read.h, trace/mesh_hit.h): the readers on
// good and hostile files, a cube mesh against the box shape, and the round trip of `softtrace
// mesh` to OBJ and PLY loaded back as mesh objects against the field's own render.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cli_util.h"
#include "io/mesh_read.h"
#include "render/camera.h"
#include "render/frame.h"
#include "scene/scene.h"

namespace softtrace {
namespace {

using test::read_file;
using test::run_softtrace;
using test::source_path;
using test::temp_dir;

// Whether each pixel centre's camera ray hits anything, at width x height.
std::vector<int> hit_mask(const Scene& scene, int width, int height) {
  const TracedScene rt(scene, LipschitzMode::Local);
  const ViewCamera camera(scene.camera, width, height);
  std::vector<int> mask(size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      mask[size_t(y) * width + x] =
          rt.embree.intersect(camera.generate(x + 0.5, y + 0.5), 0, INFINITY).hit;
  return mask;
}

// Intersection over union of two masks' hit pixels; `hits` receives the union's size.
double iou(const std::vector<int>& a, const std::vector<int>& b, long& hits) {
  long both = 0, any = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    both += a[i] && b[i];
    any += a[i] || b[i];
  }
  hits = any;
  return any ? double(both) / double(any) : 1;
}

const char* const kCubeObj = R"(# a cube, 6 quads (counter-clockwise from outside)
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(MeshRead, ObjFacesNormalsAndRelativeIndices) {
  const MeshData m = read_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\nvn 0 0 1\nvt 0 0\ng top\n"
      "f 1//1 2//1 3//1 4//1\nf -4/1/-1 -2/1/-1 -1/1/-1\n",
      "q.obj");
  ASSERT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.faces.size(), 3u);  // the quad as a fan of two, and one triangle
  EXPECT_EQ(m.faces[1], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m.faces[2], (std::array<uint32_t, 3>{0, 2, 3}));
  ASSERT_EQ(m.face_normals.size(), 3u);  // every corner has a normal: smooth
  EXPECT_EQ(m.normals[0].z, 1);
  // One face without normals makes the whole mesh flat.
  EXPECT_TRUE(read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n", "f.obj")
                  .face_normals.empty());
}

TEST(MeshRead, PlyTextAndBinaryOfEitherOrder) {
  const MeshData text = read_ply(
      "ply\nformat ascii 1.0\ncomment x\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n4 0 1 2 3\n",
      "t.ply");
  EXPECT_EQ(text.faces.size(), 2u);
  EXPECT_EQ(text.face_normals.size(), 2u);
  EXPECT_EQ(text.positions[2].y, 1);
  // The same triangle big-endian, with an element of its own to read past.
  std::string big =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement edge 1\nproperty list uchar short idx\nelement face 1\n"
      "property list uchar uint vertex_index\nend_header\n";
  const auto put_be = [&](const void* p, size_t n) {
    const auto* b = static_cast<const char*>(p);
    for (size_t k = 0; k < n; ++k) big.push_back(b[n - 1 - k]);
  };
  for (const double v : {0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 3.0, 0.0}) put_be(&v, 8);
  big += std::string("\x02\x00\x01\x00\x02", 5);
  big.push_back(3);
  for (const uint32_t i : {0u, 1u, 2u}) put_be(&i, 4);
  const MeshData b = read_ply(big, "b.ply");
  ASSERT_EQ(b.faces.size(), 1u);
  EXPECT_EQ(b.positions[1].x, 2);
  EXPECT_EQ(b.positions[2].y, 3);
  EXPECT_TRUE(b.face_normals.empty());
}

// Each hostile file is refused with one message that starts with its place.
TEST(MeshRead, HostileFilesAreRefusedAtTheirPlace) {
  const std::pair<std::string, std::string> obj[] = {
      {"v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "m.obj:3: expected a finite number, not 'nan'"},
      {"v 0 0 0\nv 1 x 0\n", "m.obj:2: expected a number, not 'x'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
       "m.obj:4: vertex index 9 out of range (the file has 3 vertices)"},
      {"v 0 0 0\nf 1 -3 1\n", "m.obj:2: vertex index -3 out of range (only 1 before it)"},
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", "m.obj:3: expected a face of at least 3 corners, not 2"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "m.obj:4: a vertex index of 0"},
      {"v 0 0\n", "m.obj:1: expected 3 numbers for a vertex"},
      {"v 0 0 0\nbogus 1\n", "m.obj:2: unknown statement 'bogus'"},
      {"cstype bezier\n", "m.obj:1: free-form geometry ('cstype') is not supported"},
      {"# nothing\n", "m.obj:1: no faces"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n", "m.obj:4: vertex index 99999999999 out"},
  };
  for (const auto& [text, expect] : obj) {
    try {
      read_obj(text, "m.obj");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const MeshReadError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(expect, 0), 0u) << e.what();
    }
  }
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::pair<std::string, std::string> ply[] = {
      {head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "m.ply:13: vertex index 3 out of range (the file has 3 vertices)"},
      {head + "0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n", "m.ply:11: expected a finite number, not 'inf'"},
      {head + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "m.ply:13: the file ends inside face 0"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
       "float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n",
       "m.ply:7: 4000000000 records of element 'face': more than 16777216"},
      {"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
       "y\nproperty float z\nelement face 1000000\nproperty list uchar int vertex_indices\n"
       "end_header\n",
       "m.ply:3: the file is too short for 3 records of element 'vertex'"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face "
       "1\nproperty list uchar int vertex_indices\nend_header\n",
       "m.ply:3: the vertex element has no scalar property 'z'"},
      {"plx\n", "m.ply:1: not a PLY file"},
  };
  for (const auto& [text, expect] : ply) {
    try {
      read_ply(text, "m.ply");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const MeshReadError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(expect, 0), 0u) << e.what();
    }
  }
}

// The cube's 12 triangles, placed as the box shape is, show the box's silhouette.
TEST(MeshObjects, ACubeMeshHasTheBoxShapesSilhouette) {
  const std::string dir = temp_dir("mesh_cube");
  write(dir + "/cube.obj", kCubeObj);
  const std::string camera = R"("camera": {"eye": [5, -7, 4], "target": [0, 0, 0], "fov": 35},)";
  const std::string place =
      R"("scale": [1, 1.5, 0.8], "rotate": {"axis": [1, 1, 0], "deg": 30}, "translate": [0.3, 0, 0])";
  const std::string mesh_scene =
      "{" + camera + R"("objects": [{"mesh": "cube.obj", )" + place + "}]}";
  const std::string box_scene =
      "{" + camera + R"("objects": [{"shape": {"type": "box", )" + place + "}}]}";
  write(dir + "/mesh.json", mesh_scene);
  const Scene with_mesh = load_scene(dir + "/mesh.json");
  ASSERT_TRUE(with_mesh.objects[0].mesh);
  EXPECT_EQ(with_mesh.objects[0].mesh->triangles(), 12u);
  const Scene with_box = parse_scene(box_scene, "box.json");
  long hits = 0;
  const double overlap = iou(hit_mask(with_mesh, 320, 240), hit_mask(with_box, 320, 240), hits);
  EXPECT_GT(hits, 5000);
  EXPECT_GE(overlap, 0.999) << hits << " pixels hit";
  RecordProperty("iou", std::to_string(overlap));
}

// A field meshed by `softtrace mesh` and loaded back as a mesh object, OBJ and PLY: the same
// silhouette as the field's own render, and hits shaded with the file's normals.
TEST(MeshObjects, SofttraceMeshRoundTripsThroughObjAndPly) {
  const std::string dir = temp_dir("mesh_round_trip");
  const std::string scene_path = source_path(test::kDefaultScene);
  const Scene field = load_scene(scene_path);
  const std::vector<int> field_mask = hit_mask(field, 160, 120);
  for (const char* ext : {"obj", "ply"}) {
    const std::string out = dir + "/blob." + ext;
    const test::RunResult r =
        run_softtrace("mesh " + scene_path + " -o " + out + " --cells 128 --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    const Vec3& eye = field.camera.eye;
    const Vec3& target = field.camera.target;
    char camera[256];
    std::snprintf(camera, sizeof camera,
                  R"("camera": {"eye": [%.17g, %.17g, %.17g], "target": [%.17g, %.17g, %.17g], )"
                  R"("fov": %.17g},)",
                  eye.x, eye.y, eye.z, target.x, target.y, target.z, field.camera.fov);
    write(dir + "/scene.json",
          "{" + std::string(camera) + R"("objects": [{"mesh": "blob.)" + ext + R"("}]})");
    const Scene mesh = load_scene(dir + "/scene.json");
    EXPECT_FALSE(mesh.objects[0].mesh->normal_indices.empty()) << ext << ": normals were kept";
    long hits = 0;
    const double overlap = iou(hit_mask(mesh, 160, 120), field_mask, hits);
    EXPECT_GT(hits, 2000) << ext;
    EXPECT_GE(overlap, 0.99) << ext;
    RecordProperty(std::string("iou_") + ext, std::to_string(overlap));
  }
}

// A mesh's hit: its distance in double on the triangle's plane, and the interpolated normal.
TEST(MeshObjects, HitsLieOnTheTrianglesAndTakeTheFilesNormals) {
  const std::string dir = temp_dir("mesh_hit");
  write(dir + "/tilted.obj",
        "v -2 -2 0\nv 2 -2 1\nv 0 2 0.5\nvn 0 0 1\nvn 0.6 0 0.8\nvn 0 0.6 0.8\n"
        "f 1//1 2//2 3//3\n");
  write(dir + "/s.json",
        R"({"camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "up": [0, 1, 0]},
            "objects": [{"mesh": "tilted.obj"}]})");
  const Scene scene = load_scene(dir + "/s.json");
  const TracedScene rt(scene, LipschitzMode::Local);
  int checked = 0;
  for (double x = -0.6; x <= 0.61; x += 0.3)
    for (double y = -1.5; y <= 0.01; y += 0.3) {
      const Ray ray{{x, y, 10}, {0, 0, -1}, 0, 0};
      const TraceHit h = rt.embree.intersect(ray, 0, INFINITY);
      ASSERT_TRUE(h.hit);
      // The plane through the three vertices: normal (v1 - v0) x (v2 - v0).
      const Vec3 v0{-2, -2, 0}, n = cross(Vec3{4, 0, 1}, Vec3{2, 4, 0.5});
      const Vec3 p = ray.o + ray.d * h.t;
      EXPECT_NEAR(dot(p - v0, n) / length(n), 0, 1e-12);
      // Barycentrics of p, then the normals mixed by them.
      const Vec3 e1{4, 0, 1}, e2{2, 4, 0.5}, q = p - v0;
      const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
      const double q1 = dot(q, e1), q2 = dot(q, e2), den = d11 * d22 - d12 * d12;
      const double u = (d22 * q1 - d12 * q2) / den, v = (d11 * q2 - d12 * q1) / den;
      const Vec3 expect =
          normalize(Vec3{0, 0, 1} * (1 - u - v) + Vec3{0.6, 0, 0.8} * u + Vec3{0, 0.6, 0.8} * v);
      EXPECT_NEAR(dot(h.normal, expect), 1, 1e-6) << x << " " << y;
      ++checked;
    }
  EXPECT_EQ(checked, 30);
}

TEST(MeshObjects, TheLoaderNamesTheFileLineAndTheKey) {
  const std::string dir = temp_dir("mesh_errors");
  write(dir + "/bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  write(dir + "/far.obj", kCubeObj);
  const auto error = [&](const std::string& objects) {
    write(dir + "/s.json",
          R"({"camera": {"eye": [5, 5, 5], "target": [0, 0, 0]}, "objects": )" + objects + "}");
    try {
      load_scene(dir + "/s.json");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error(R"([{"mesh": "bad.obj"}])"),
            dir + "/bad.obj:4: vertex index 4 out of range (the file has 3 vertices) (read for " +
                dir + "/s.json: /objects/0/mesh)");
  EXPECT_EQ(
      error(R"([{"mesh": "none.obj"}])"),
      dir + "/none.obj: cannot open the mesh file (read for " + dir + "/s.json: /objects/0/mesh)");
  EXPECT_NE(error(R"([{"mesh": "far.obj", "translate": [1e12, 0, 0]}])")
                .find("/s.json: /objects/0/mesh: " + dir + "/far.obj: vertex 2 is placed beyond"),
            std::string::npos);
  EXPECT_NE(error(R"([{"mesh": "far.obj", "iso": 1}])").find("/objects/0/iso: an object with a"),
            std::string::npos);
  EXPECT_NE(error(R"([{"shape": {"type": "sphere"}, "translate": [1, 0, 0]}])")
                .find("/objects/0/translate: 'translate' places a mesh or a CSG object"),
            std::string::npos);
  // A closed mesh is a CSG operand (open ones are refused: test_mesh_csg.cpp).
  EXPECT_EQ(error(R"([{"csg": "union", "operands": [{"mesh": "far.obj"},
                                                     {"shape": {"type": "sphere"}}]}])"),
            "accepted");
}

}  // namespace
}  // namespace softtrace

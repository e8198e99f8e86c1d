// Closed triangle meshes as CSG operands (trace/mesh_crossings.h, scene/mesh_closure.h): a cube
// mesh in a CSG draws what the box shape draws in its place, to rounding (hits, depths, normals,
// faces), for every operation, placed and turned, with its triangles facing inward, as two shells
// in one file and as a hollow one; a blob minus a mesh against the blob minus the box; and the
// loader's refusals of meshes with no inside, at the operand's pointer, exit status 2.
#include <gtest/gtest.h>

#include <fstream>

#include "cli_util.h"
#include "render/camera.h"
#include "render/frame.h"
#include "scene/scene.h"
#include "scene/traced_objects.h"
#include "trace/csg_trace.h"

namespace softtrace {
namespace {

// A cube [-1, 1]^3 as 6 quads, counter-clockwise seen from outside; `offset` is added to the
// vertex numbers (a second shell in the same file), `inward` writes every face the other way.
std::string cube_obj(double cx, double cy, double cz, double r, int offset, bool inward) {
  std::string s;
  for (int i = 0; i < 8; ++i) {
    const double x = (i == 1 || i == 2 || i == 5 || i == 6) ? 1 : -1;
    const double y = (i == 2 || i == 3 || i == 6 || i == 7) ? 1 : -1;
    const double z = i >= 4 ? 1 : -1;
    s += "v " + std::to_string(cx + r * x) + " " + std::to_string(cy + r * y) + " " +
         std::to_string(cz + r * z) + "\n";
  }
  const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                           {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
  for (const auto& f : faces) {
    s += "f";
    for (int k = 0; k < 4; ++k) s += " " + std::to_string(offset + f[inward ? 3 - k : k]);
    s += "\n";
  }
  return s;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

const std::string kBlobOperand = R"({"name": "blob", "field": {"type": "soft_blend", "children": [
  {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [9, 9, 9], "n": 2}},
  {"type": "soft_object", "translate": [4, 2, 3],
   "distance": {"type": "lp_metric", "radii": [6, 6, 6], "n": 2}}]}})";

struct Pair {
  const char* name;
  std::string with_mesh, with_shapes;  // the same CSG object, with the mesh and with shapes
};

std::vector<Pair> pairs() {
  const std::string ball = R"({"name": "ball", "shape": {"type": "sphere", "radius": 6.5}})";
  const std::string cube = R"({"name": "cut", "mesh": "cube.obj", "scale": [5, 5, 5],
                                "translate": [3, -3, 3]})";
  const std::string box = R"({"name": "cut", "shape": {"type": "box", "corner1": [-2, -8, -2],
                               "corner2": [8, 2, 8]}})";
  const std::string turned_cube = R"({"name": "cut", "mesh": "cube.obj", "scale": [5, 3, 4],
                                      "rotate": {"axis": [1, 2, 3], "deg": 37}})";
  const std::string turned_box = R"({"name": "cut", "shape": {"type": "box",
      "corner1": [-5, -3, -4], "corner2": [5, 3, 4], "rotate": {"axis": [1, 2, 3], "deg": 37}}})";
  const auto csg = [](const std::string& op, const std::string& a, const std::string& b) {
    return R"({"csg": ")" + op + R"(", "operands": [)" + a + ", " + b + "]}";
  };
  std::vector<Pair> out;
  for (const char* op : {"union", "intersection", "difference"})
    out.push_back({op, csg(op, ball, cube), csg(op, ball, box)});
  out.push_back({"turned_difference", csg("difference", ball, turned_cube),
                 csg("difference", ball, turned_box)});
  out.push_back({"inward_faces",
                 csg("difference", ball,
                     R"({"name": "cut", "mesh": "inward.obj", "scale": [5, 5, 5],
                                         "translate": [3, -3, 3]})"),
                 csg("difference", ball, box)});
  // Two shells in one file: a union of two boxes (cut out of the ball).
  const std::string two_boxes =
      R"({"csg": "union", "operands": [
           {"name": "a", "shape": {"type": "box", "corner1": [-7, -7, -7], "corner2": [-1, -1, -1]}},
           {"name": "a", "shape": {"type": "box", "corner1": [1, 1, 1], "corner2": [7, 7, 7]}}]})";
  out.push_back({"two_shells", csg("difference", ball, R"({"name": "a", "mesh": "two.obj"})"),
                 csg("difference", ball, two_boxes)});
  // A hollow: an outer shell and an inner one turned inward, a box minus a box.
  const std::string hollow_boxes =
      R"({"csg": "difference", "operands": [
           {"name": "a", "shape": {"type": "box", "corner1": [-6, -6, -6], "corner2": [6, 6, 6]}},
           {"name": "a", "shape": {"type": "box", "corner1": [-4, -4, -4], "corner2": [4, 4, 4]}}]})";
  out.push_back({"hollow", csg("difference", R"({"name": "a", "mesh": "hollow.obj"})", ball),
                 csg("difference", hollow_boxes, ball)});
  // A blob minus the cube.
  out.push_back({"blob_minus_mesh", csg("difference", kBlobOperand, cube),
                 csg("difference", kBlobOperand, box)});
  return out;
}

class MeshOperand : public testing::TestWithParam<int> {};

// Pixel by pixel, the first hit of the CSG with the mesh and with the shapes: the same hits
// (IoU 1), the same depths and normals, faces of the same name (the shapes that stand for one
// mesh share its name). A mesh's placed vertices are floats: a turned cube's corners are off by
// their rounding, 6e-8 of coordinates below 10, so depths agree to 1e-6 and normals to 1e-6.
TEST_P(MeshOperand, DrawsWhatTheShapesDraw) {
  const Pair p = pairs()[GetParam()];
  const std::string dir = test::temp_dir(std::string("mesh_operand_") + p.name);
  write_text(dir + "/cube.obj", cube_obj(0, 0, 0, 1, 0, false));
  write_text(dir + "/inward.obj", cube_obj(0, 0, 0, 1, 0, true));
  write_text(dir + "/two.obj", cube_obj(-4, -4, -4, 3, 0, false) + cube_obj(4, 4, 4, 3, 8, false));
  write_text(dir + "/hollow.obj", cube_obj(0, 0, 0, 6, 0, false) + cube_obj(0, 0, 0, 4, 8, true));
  const auto load = [&](const std::string& object, const std::string& name) {
    write_text(
        dir + "/" + name,
        R"({"camera": {"eye": [30, -40, 20], "target": [1, -1, 1], "fov": 30}, "objects": [)" +
            object + "]}");
    return load_scene(dir + "/" + name);
  };
  const Scene a = load(p.with_mesh, "mesh.json"), b = load(p.with_shapes, "shapes.json");
  const CsgTracer ta(traced_object(a.objects[0]), LipschitzMode::Local);
  const CsgTracer tb(traced_object(b.objects[0]), LipschitzMode::Local);
  const int w = 96, h = 72;
  const ViewCamera camera(a.camera, w, h);
  long both = 0, any = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      SCOPED_TRACE(std::to_string(x) + "," + std::to_string(y));
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      TraceCounters work;
      const CsgHit ha = ta.first_hit(ray, 0, 1e3, work), hb = tb.first_hit(ray, 0, 1e3, work);
      both += ha.hit && hb.hit;
      any += ha.hit || hb.hit;
      if (!ha.hit || !hb.hit) continue;
      EXPECT_NEAR(ha.t, hb.t, 1e-6);
      EXPECT_NEAR(dot(ha.normal, hb.normal), 1, 1e-6);
      EXPECT_EQ(face_object(a.objects[0], ha.face).name, face_object(b.objects[0], hb.face).name);
      // Shadow rays from inside the solid out (the ray starts inside the mesh): the same exit.
      const Ray back{ray.o + ray.d * (hb.t + 1e-3), ray.d, 0, 0};
      const CsgHit ea = ta.first_hit(back, 0, 1e3, work), eb = tb.first_hit(back, 0, 1e3, work);
      ASSERT_EQ(ea.hit, eb.hit);
      if (ea.hit) {
        EXPECT_NEAR(ea.t, eb.t, 1e-6);
      }
    }
  ASSERT_GT(any, w * h / 20) << "the object should fill part of the frame";
  EXPECT_EQ(both, any) << "IoU " << double(both) / double(any);
  RecordProperty("hits", int(any));
}

INSTANTIATE_TEST_SUITE_P(Cases, MeshOperand, testing::Range(0, int(pairs().size())),
                         [](const testing::TestParamInfo<int>& i) {
                           return std::string(pairs()[i.param].name);
                         });

// A mesh with no inside is refused where the operand names it, with the edge that shows it.
TEST(MeshOperandLoader, ARefusedMeshNamesTheOperandAndTheEdge) {
  const std::string dir = test::temp_dir("mesh_operand_errors");
  const std::string cube = cube_obj(0, 0, 0, 1, 0, false);
  write_text(dir + "/open.obj", cube.substr(0, cube.rfind("f ")));  // the last face left out
  write_text(dir + "/twisted.obj",
             cube.substr(0, cube.rfind("f ")) + "f 4 8 5 1\n");  // turned over
  write_text(dir + "/fin.obj", cube + "v 0 0 5\nf 1 2 9\n");     // a third triangle on an edge
  write_text(dir + "/flat.obj", "v 0 0 0\nv 1 0 0\nv 0 0 0\nf 1 2 3\n");
  const auto error = [&](const std::string& file) {
    write_text(dir + "/s.json", R"({"camera": {"eye": [5, 5, 5], "target": [0, 0, 0]},
      "objects": [{"csg": "difference", "operands": [{"shape": {"type": "sphere"}},
                                                      {"mesh": ")" +
                                    file + R"("}]}]})");
    return test::run_softtrace("render " + dir + "/s.json -q -o " + dir + "/s.exr");
  };
  const std::string where = dir + "/s.json: /objects/0/operands/1/mesh: a CSG operand must be a " +
                            "closed mesh (its inside is what the CSG combines), but ";
  const test::RunResult open = error("open.obj");
  EXPECT_EQ(open.status, 2);
  EXPECT_NE(open.err.find(where + "its edge from vertex 1 to vertex 4 borders one triangle only "
                                  "(the mesh is open)"),
            std::string::npos)
      << open.err;
  const test::RunResult twisted = error("twisted.obj");
  EXPECT_EQ(twisted.status, 2);
  EXPECT_NE(
      twisted.err.find(where + "its edge from vertex 1 to vertex 4 is run along the same way"),
      std::string::npos)
      << twisted.err;
  const test::RunResult fin = error("fin.obj");
  EXPECT_EQ(fin.status, 2);
  EXPECT_NE(fin.err.find(where + "its edge from vertex 1 to vertex 2 borders 3 triangles"),
            std::string::npos)
      << fin.err;
  const test::RunResult flat = error("flat.obj");
  EXPECT_EQ(flat.status, 2);
  EXPECT_NE(flat.err.find(where + "its triangles have no area"), std::string::npos) << flat.err;
  EXPECT_FALSE(std::ifstream(dir + "/s.exr").good()) << "no image from a refused scene";
  // The same files as objects of their own are drawn (an open mesh is a surface).
  write_text(dir + "/own.json", R"({"camera": {"eye": [5, 5, 5], "target": [0, 0, 0]},
      "objects": [{"mesh": "open.obj"}]})");
  EXPECT_EQ(test::run_softtrace("render " + dir + "/own.json -q --width 8 --height 6 -o " + dir +
                                "/own.exr")
                .status,
            0);
}

}  // namespace
}  // namespace softtrace

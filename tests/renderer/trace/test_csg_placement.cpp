// A CSG object's placement keys (scene.h Csg, trace/csg_trace.h, the TracedObject placement of
// scene/trace_target.h): a placed tree, nested placements included, renders as the same tree with
// every operand placed on its own by the composed map (a field by its node's `matrix`, a shape by
// its shape's), pixel by pixel: the same silhouette, the same depths and normals to the tracer's
// tolerance, the same face materials.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "math/affine.h"
#include "render/camera.h"
#include "render/frame.h"
#include "render/shading.h"
#include "scene/scene.h"
#include "scene/traced_objects.h"

namespace softtrace {
namespace {

// The 3 rows [a, b, c, t] of a map, as the `matrix` key reads.
std::string matrix_json(const Affine& m) {
  std::string s = "[";
  for (int i = 0; i < 3; ++i) {
    char row[160];
    std::snprintf(row, sizeof row, "%s[%.17g, %.17g, %.17g, %.17g]", i ? ", " : "", m.linear.r[i].x,
                  m.linear.r[i].y, m.linear.r[i].z, m.offset[i]);
    s += row;
  }
  return s + "]";
}

const char* const kBlob = R"("type": "soft_blend", "children": [
    {"type": "soft_object", "translate": [0, 0, 2],
     "distance": {"type": "lp_metric", "radii": [3, 3, 3], "n": 2}},
    {"type": "soft_object", "translate": [1.5, 1, 3.5],
     "distance": {"type": "lp_metric", "radii": [2, 2, 2], "n": 2}}])";
const char* const kHeader = R"({"camera": {"eye": [14, -18, 12], "target": [1, 0, 2], "fov": 24},
  "objects": [)";

TEST(CsgPlacement, APlacedTreeRendersAsItsOperandsPlacedOneByOne) {
  // The outer CSG: scale, then rotate, then translate; the inner one: rotate, then translate.
  const std::string outer_keys =
      R"("scale": [1.2, 0.8, 1], "rotate": {"axis": [0, 0, 1], "deg": 30},
                                    "translate": [2, -1, 0.5])";
  const std::string inner_keys =
      R"("rotate": {"axis": [1, 0, 0], "deg": 15}, "translate": [0, 0, 1])";
  const Affine P{times(Mat3::rotation({0, 0, 1}, 30), Mat3{{{1.2, 0, 0}, {0, 0.8, 0}, {0, 0, 1}}}),
                 {2, -1, 0.5}};
  const Affine Q{Mat3::rotation({1, 0, 0}, 15), {0, 0, 1}};
  const std::string plane = R"("type": "plane", "normal": [-0.7, 0.5, -0.5], "distance": -1.5)";
  const std::string box = R"("type": "box", "corner1": [-4, -2, 0], "corner2": [-1, 1, 2])";
  const std::string placed = std::string(kHeader) + R"({"name": "all", "csg": "merge", )" +
                             outer_keys +
                             R"(, "material": {"color": [0.7, 0.7, 0.3]}, "operands": [
        {"name": "cut", "csg": "difference", )" +
                             inner_keys + R"(, "operands": [
          {"name": "blob", "material": {"color": [0.9, 0.4, 0.3]}, "field": {)" +
                             kBlob + R"(}},
          {"name": "knife", "shape": {)" +
                             plane + R"(}}]},
        {"name": "crate", "shape": {)" +
                             box + R"(}}]}]})";
  const Affine PQ = compose(P, Q);
  const std::string one_by_one =
      std::string(kHeader) +
      R"({"name": "all", "csg": "merge", "material": {"color": [0.7, 0.7, 0.3]}, "operands": [
        {"name": "cut", "csg": "difference", "operands": [
          {"name": "blob", "material": {"color": [0.9, 0.4, 0.3]}, "field": {)" +
      kBlob + R"(, "matrix": )" + matrix_json(PQ) + R"(}},
          {"name": "knife", "shape": {)" +
      plane + R"(, "matrix": )" + matrix_json(PQ) + R"(}}]},
        {"name": "crate", "shape": {)" +
      box + R"(, "matrix": )" + matrix_json(P) + R"(}}]}]})";
  const Scene a = parse_scene(placed, "placed.json"), b = parse_scene(one_by_one, "apart.json");
  ASSERT_TRUE(a.objects[0].csg->placed);
  const TracedScene ra(a, LipschitzMode::Local), rb(b, LipschitzMode::Local);
  constexpr int kW = 160, kH = 120;
  const ViewCamera camera(a.camera, kW, kH);
  long both = 0, any = 0, far_depth = 0, bent = 0, other_face = 0;
  bool faces[3] = {false, false, false};  // blob, knife, crate seen
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit ha = ra.embree.intersect(ray, 0, INFINITY);
      const TraceHit hb = rb.embree.intersect(ray, 0, INFINITY);
      any += ha.hit || hb.hit;
      if (!(ha.hit && hb.hit)) continue;
      ++both;
      // The tracer places a hit within 1/1000 of the footprint; a pixel here is ~0.1 wide.
      far_depth += std::abs(ha.t - hb.t) > 1e-3;
      bent += dot(ha.normal, hb.normal) < 0.999;
      const std::string& face = face_object(a.objects[0], ha.face).name;
      other_face += face != face_object(b.objects[0], hb.face).name;
      for (int k = 0; k < 3; ++k)
        faces[k] = faces[k] || face == (const char*[]){"blob", "knife", "crate"}[k];
    }
  EXPECT_GT(both, 3000);
  EXPECT_GE(double(both) / double(any), 0.999) << both << " of " << any;
  EXPECT_LE(far_depth, both / 1000) << far_depth;
  EXPECT_LE(bent, both / 1000) << bent;
  EXPECT_LE(other_face, both / 1000) << other_face;
  EXPECT_TRUE(faces[0] && faces[1] && faces[2]) << "every operand's surface is in view";
  RecordProperty("iou", std::to_string(double(both) / double(any)));
}

TEST(CsgPlacement, APlacedCsgsBoxIsItsOperandsBoxPlaced) {
  const Scene s = parse_scene(std::string(kHeader) + R"({"csg": "union", "translate": [10, 0, 0],
      "scale": [2, 2, 2], "operands": [{"shape": {"type": "sphere", "radius": 1}},
                                       {"shape": {"type": "sphere", "center": [0, 0, 3]}}]}]})",
                              "box.json");
  const Box& b = s.objects[0].bounds;
  EXPECT_EQ(b.lo.x, 8);
  EXPECT_EQ(b.hi.x, 12);
  EXPECT_EQ(b.lo.z, -2);
  EXPECT_EQ(b.hi.z, 8);
}

// A placed CSG's field operand mixes its components' materials at the point in its own frame:
// the tree moved by 10 along x, seen from a camera moved with it, shades every pixel as before.
TEST(CsgPlacement, ComponentMaterialsAreWeighedInTheOperandsFrame) {
  const auto scene = [](const std::string& eye, const std::string& target,
                        const std::string& placement) {
    return parse_scene(R"({"camera": {"eye": )" + eye + R"(, "target": )" + target +
                           R"(, "fov": 30},
        "lights": [{"type": "directional", "direction": [-1, 0.5, -1]}],
        "objects": [{"csg": "union", )" +
                           placement + R"("operands": [
          {"material": {"color": [0.5, 0.5, 0.5]}, "field": {"type": "soft_blend", "children": [
            {"type": "soft_object", "material": {"color": [0.9, 0.1, 0.1]},
             "distance": {"type": "lp_metric", "radii": [3, 3, 3], "n": 2}},
            {"type": "soft_object", "translate": [3, 0, 0], "material": {"color": [0.1, 0.1, 0.9]},
             "distance": {"type": "lp_metric", "radii": [3, 3, 3], "n": 2}}]}},
          {"shape": {"type": "box", "corner1": [-1, -1, -5], "corner2": [4, 1, -2]}}]}]})",
                       "weights.json");
  };
  const Scene here = scene("[1.5, -20, 6]", "[1.5, 0, 0]", "");
  const Scene moved = scene("[11.5, -20, 6]", "[11.5, 0, 0]", R"("translate": [10, 0, 0], )");
  const TracedScene rh(here, LipschitzMode::Local), rm(moved, LipschitzMode::Local);
  constexpr int kW = 64, kH = 48;
  const ViewCamera ch(here.camera, kW, kH), cm(moved.camera, kW, kH);
  RayWork shadow;
  long compared = 0, differ = 0;
  double reddest = 0, bluest = 0;  // the components' colours both show
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const Ray a = ch.generate(x + 0.5, y + 0.5), b = cm.generate(x + 0.5, y + 0.5);
      const TraceHit ha = rh.embree.intersect(a, 0, INFINITY);
      const TraceHit hb = rm.embree.intersect(b, 0, INFINITY);
      if (!ha.hit || !hb.hit ||
          &face_object(here.objects[0], ha.face) != &here.objects[0].csg->operands[0])
        continue;
      const Vec3 ca = shade(here, rh.tracers, rh.embree, a, ha, shadow).color;
      const Vec3 cb = shade(moved, rm.tracers, rm.embree, b, hb, shadow).color;
      ++compared;
      differ += max_abs(ca - cb) > 1e-3;
      reddest = std::max(reddest, ca.x - ca.z);
      bluest = std::max(bluest, ca.z - ca.x);
    }
  EXPECT_GT(compared, 200);
  EXPECT_LE(differ, compared / 100) << differ << " of " << compared;
  EXPECT_GT(reddest, 0.2);
  EXPECT_GT(bluest, 0.2);
}

}  // namespace
}  // namespace softtrace

// CSG objects (scene.h Csg, trace/csg_trace.h) against a dense reference march of the same solid:
// along every pixel's ray the first surface the tracer reports is where the march, stepping far
// finer than the thinnest part, first finds a point inside (no holes, no false surfaces), and
// the shadow ray each hit sends towards the light is blocked exactly where the march along it
// finds the solid (no acne). The cases are the thin and tangent ones where CSG goes wrong: a blob
// minus a thin box, a blob cut to a slab thinner than a pixel, a grazing view along a cut face,
// a blob exactly tangent to a plane. Also the loader's materials and boxes.
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "cli_util.h"
#include "io/image_file.h"
#include "render/camera.h"
#include "scene/scene.h"
#include "scene/traced_objects.h"
#include "trace/csg_trace.h"

namespace softtrace {
namespace {

const std::string kBlob = R"({"type": "soft_blend", "children": [
  {"type": "soft_object", "distance": {"type": "lp_metric", "radii": [9, 9, 9], "n": 2}},
  {"type": "soft_object", "translate": [4, 2, 3],
   "distance": {"type": "lp_metric", "radii": [6, 6, 6], "n": 2}}]})";

// Membership of a point in an object's solid, from the definitions: a field inside its box where
// g >= 0, a shape from its own space (planes, boxes and spheres are what the cases use), a CSG
// by its operation.
class Membership {
 public:
  explicit Membership(const SceneObject& root) { add(root); }
  bool inside(const SceneObject& o, const Vec3& p) const {
    if (o.field) return o.bounds.contains(p) && tracers_.at(&o)->inside(p);
    if (o.shape) {
      const Primitive& s = *o.shape;
      const Vec3 q = s.to_object * (p - s.to_world.offset);
      switch (s.shape) {
        case Primitive::Shape::Plane:
          return dot(s.normal, q) <= s.distance;
        case Primitive::Shape::Box:
          return Box(s.a, s.b).contains(q);
        case Primitive::Shape::Sphere:
          return length(q - s.a) <= s.r0;
        case Primitive::Shape::Cylinder:
        case Primitive::Shape::Cone:
        case Primitive::Shape::Disc:
          ADD_FAILURE() << "no reference membership for this shape";
          return false;
      }
    }
    const auto& ops = o.csg->operands;
    switch (o.csg->op) {
      case Csg::Op::Union:
      case Csg::Op::Merge:
        for (const SceneObject& a : ops)
          if (inside(a, p)) return true;
        return false;
      case Csg::Op::Intersection:
        for (const SceneObject& a : ops)
          if (!inside(a, p)) return false;
        return true;
      case Csg::Op::Difference:
        if (!inside(ops[0], p)) return false;
        for (size_t i = 1; i < ops.size(); ++i)
          if (inside(ops[i], p)) return false;
        return true;
    }
    return false;
  }

 private:
  void add(const SceneObject& o) {
    if (o.field)
      tracers_[&o] = std::make_unique<ObjectTracer>(trace_target(o), LipschitzMode::Local);
    if (o.csg)
      for (const SceneObject& a : o.csg->operands) add(a);
  }
  std::map<const SceneObject*, std::unique_ptr<ObjectTracer>> tracers_;
};

struct MarchHit {
  bool hit = false;
  double t = 0;
};
// The first sample inside the solid along [t0, t1] (clipped to the object's box), every `step`.
MarchHit march(const Membership& m, const SceneObject& o, const Ray& ray, double t0, double t1,
               double step) {
  if (!clip_to_box(ray, o.bounds, t0, t1)) return {};
  for (double t = t0; t <= t1; t += step)
    if (m.inside(o, ray.o + ray.d * t)) return {true, t};
  return {};
}

struct Case {
  const char* name;
  std::string object;  // the CSG object's JSON
  Vec3 eye, target;
  double step;  // the march's step: far below the thinnest part of the solid
};

std::string scene_text(const Case& c) {
  const auto v = [](const Vec3& p) {
    return "[" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
           "]";
  };
  return R"({"camera": {"eye": )" + v(c.eye) + R"(, "target": )" + v(c.target) +
         R"(, "fov": 20}, "objects": [)" + c.object + "]}";
}

// The top of the blob's surface above the origin, to rounding (by bisection on f - iso).
double blob_top() {
  const Scene s = parse_scene(R"({"camera": {"eye": [40, 0, 0], "target": [0, 0, 0]},
    "objects": [{"field": )" + kBlob +
                                  "}]}",
                              "top.json");
  const ObjectTracer tr(trace_target(s.objects[0]), LipschitzMode::Local);
  double lo = 0, hi = 20;  // inside at the origin, outside at 20
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (tr.inside({0, 0, mid}) ? lo : hi) = mid;
  }
  return lo;
}

std::vector<Case> cases() {
  const std::string blob = R"({"name": "blob", "field": )" + kBlob + "}";
  const double top = blob_top();
  char tangent[64];
  std::snprintf(tangent, sizeof tangent, "%.17g", top);
  return {
      {"blob_minus_thin_box",
       R"({"csg": "difference", "operands": [)" + blob +
           R"(, {"shape": {"type": "box", "corner1": [-20, -0.05, -20], "corner2": [20, 0.05, 20],
               "rotate": {"axis": [1, 0, 0], "deg": 30}}}]})",
       {30, -35, 18},
       {1, 1, 1},
       0.004},
      {"blob_and_subpixel_slab",
       R"({"csg": "intersection", "operands": [)" + blob +
           R"(, {"shape": {"type": "box", "corner1": [-20, -20, 2], "corner2": [20, 20, 2.03]}}]})",
       {30, -35, 22},
       {1, 1, 2},
       0.003},
      {"grazing_cut_face",
       R"({"csg": "intersection", "operands": [)" + blob +
           R"(, {"shape": {"type": "plane", "normal": [0, 0, 1], "distance": 1}}]})",
       {40, -30, 1.02},
       {0, 0, 1},
       0.005},
      {"blob_tangent_to_plane",
       R"({"csg": "difference", "operands": [)" + blob +
           R"(, {"shape": {"type": "plane", "normal": [0, 0, -1], "distance": -)" + tangent +
           R"(}}, {"shape": {"type": "sphere", "center": [6, -6, 4], "radius": 3}}]})",
       {30, -30, 14},
       {0, 0, 3},
       0.005},
  };
}

class CsgAgainstMarch : public testing::TestWithParam<int> {};

TEST_P(CsgAgainstMarch, NoHolesNoFalseSurfacesNoAcne) {
  const Case c = cases()[GetParam()];
  const Scene scene = parse_scene(scene_text(c), std::string(c.name) + ".json");
  const SceneObject& object = scene.objects[0];
  ASSERT_TRUE(object.csg);
  const CsgTracer tracer(traced_object(object), LipschitzMode::Local);
  const Membership m(object);
  const int w = 64, h = 48;
  const ViewCamera camera(scene.camera, w, h);
  const Vec3 to_light = normalize(Vec3{0.6, -1, 1.6});
  int hits = 0, shadowed = 0, checked = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      SCOPED_TRACE(std::to_string(px) + "," + std::to_string(py));
      const Ray ray = camera.generate(px + 0.5, py + 0.5);
      TraceCounters work;
      const CsgHit got = tracer.first_hit(ray, 0, 1e3, work);
      const MarchHit ref = march(m, object, ray, 0, 1e3, c.step);
      ++checked;
      ASSERT_EQ(got.hit, ref.hit) << "tracer t " << got.t << ", march t " << ref.t;
      if (!got.hit) continue;
      ++hits;
      // The march's sample is past the surface by less than a step; the tracer's hit within
      // 1/1000 of the footprint of it.
      const double slack = 1e-3 * (ray.cone0 + ray.cone * got.t) + 1e-9 * got.t;
      EXPECT_GE(got.t, ref.t - c.step - slack);
      EXPECT_LE(got.t, ref.t + slack);
      ASSERT_GT(got.face, 0);  // an operand of the object
      const SceneObject& face = face_object(object, got.face);
      EXPECT_NEAR(length(got.normal), 1, 1e-9);
      // The shadow ray leaves as shading's does (by the footprint, on the side the viewer sees)
      // and must be blocked exactly where the march finds the solid along it.
      Vec3 n = got.normal;
      if (dot(n, ray.d) > 0) n = -n;
      if (dot(n, to_light) <= 0) continue;
      const Vec3 p = ray.o + ray.d * got.t;
      const double offset =
          std::max(1e-4 * (face.field ? face.bounds.diagonal() : 0), ray.cone0 + ray.cone * got.t);
      const Ray shadow{p + n * offset, to_light, 0, 0};
      TraceCounters shadow_work;
      const bool blocked = tracer.first_hit(shadow, 0, 1e3, shadow_work).hit;
      const bool ref_blocked = march(m, object, shadow, 0, 1e3, c.step).hit;
      EXPECT_EQ(blocked, ref_blocked) << "shadow ray from t " << got.t;
      shadowed += blocked;
    }
  EXPECT_EQ(checked, w * h);
  EXPECT_GT(hits, w * h / 20) << "the object should fill part of the frame";
  RecordProperty("hits", hits);
  RecordProperty("shadowed", shadowed);
}

INSTANTIATE_TEST_SUITE_P(Cases, CsgAgainstMarch, testing::Range(0, 4),
                         [](const testing::TestParamInfo<int>& i) {
                           return std::string(cases()[i.param].name);
                         });

TEST(Csg, OperandsWithoutMaterialTakeTheEnclosingCsgs) {
  const Scene s = parse_scene(R"({"camera": {"eye": [30, 0, 0], "target": [0, 0, 0]},
    "objects": [{"csg": "union", "material": {"color": [1, 0, 0]}, "operands": [
      {"shape": {"type": "sphere", "radius": 1}},
      {"csg": "difference", "operands": [
        {"material": {"color": [0, 1, 0]}, "shape": {"type": "sphere", "radius": 2}},
        {"shape": {"type": "box", "corner1": [0, 0, 0], "corner2": [3, 3, 3]}}]}]},
      {"csg": "intersection", "operands": [
        {"shape": {"type": "sphere", "radius": 1}}, {"shape": {"type": "sphere", "radius": 1}}]}]})",
                              "m.json");
  const auto& u = s.objects[0].csg->operands;
  EXPECT_EQ(u[0].material.color.x, 1);
  const auto& d = u[1].csg->operands;
  EXPECT_EQ(d[0].material.color.y, 1);
  EXPECT_EQ(d[1].material.color.x, 1);  // the cutter: the nearest enclosing material (the union's)
  const Material grey;
  EXPECT_EQ(s.objects[1].csg->operands[0].material.color.x, grey.color.x);
}

TEST(Csg, BoxesFollowTheOperation) {
  const std::string a = R"({"shape": {"type": "box", "corner1": [0, 0, 0], "corner2": [2, 2, 2]}})";
  const std::string b = R"({"shape": {"type": "box", "corner1": [1, 1, 1], "corner2": [3, 3, 3]}})";
  const auto box = [&](const std::string& op) {
    return parse_scene(R"({"camera": {"eye": [30, 0, 0], "target": [0, 0, 0]}, "objects": [
      {"csg": ")" + op + R"(", "operands": [)" +
                           a + ", " + b + "]}]}",
                       "b.json")
        .objects[0]
        .bounds;
  };
  EXPECT_EQ(box("union").lo.x, 0);
  EXPECT_EQ(box("union").hi.x, 3);
  EXPECT_EQ(box("merge").hi.x, 3);
  EXPECT_EQ(box("intersection").lo.x, 1);
  EXPECT_EQ(box("intersection").hi.x, 2);
  EXPECT_EQ(box("difference").lo.x, 0);
  EXPECT_EQ(box("difference").hi.x, 2);
}

// A difference's cut face: the subtracted operand's normal turned, that operand's material.
TEST(Csg, ACutFaceTakesTheCuttersTurnedNormalAndMaterial) {
  const Scene s = parse_scene(R"({"camera": {"eye": [30, 0, 0], "target": [0, 0, 0]},
    "objects": [{"csg": "difference", "operands": [
      {"name": "ball", "material": {"color": [1, 0, 0]}, "field": )" +
                                  kBlob + R"(},
      {"name": "cutter", "material": {"color": [0, 0, 1]},
       "shape": {"type": "box", "corner1": [-1, -20, -20], "corner2": [40, 20, 20]}}]}]})",
                              "cut.json");
  const CsgTracer tracer(traced_object(s.objects[0]), LipschitzMode::Local);
  TraceCounters work;
  const Ray ray{{30, 0.5, 0.5}, {-1, 0, 0}, 0, 0};
  const CsgHit h = tracer.first_hit(ray, 0, 100, work);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 31, 1e-9);  // the box's face at x = -1
  EXPECT_EQ(face_object(s.objects[0], h.face).name, "cutter");
  EXPECT_NEAR(h.normal.x, 1, 1e-12);  // the box's outward normal there is -x, turned
  // Every span of the result lies in the solid, by membership at its midpoint.
  const Membership m(s.objects[0]);
  const auto spans = tracer.spans(ray, 0, 100, work);
  ASSERT_FALSE(spans.empty());
  for (const CsgSpan& sp : spans) {
    EXPECT_TRUE(m.inside(s.objects[0], ray.o + ray.d * (0.5 * (sp.t0 + sp.t1))));
    EXPECT_FALSE(m.inside(s.objects[0], ray.o + ray.d * (sp.t1 + 1e-6)));
  }
}

// POV-Ray's cutaway_textures: the face an untextured box cuts into a red blob shows the blob's
// material with the key, the default (grey) without; the traced hit names that box.
TEST(Csg, CutawayTexturesGiveTheCutFaceTheCutObjectsMaterial) {
  const auto cut_face_material = [](const std::string& key) {
    const Scene s = parse_scene(R"({"camera": {"eye": [30, 0, 0], "target": [0, 0, 0]},
      "objects": [{"csg": "difference", )" +
                                    key +
                                    R"("operands": [
        {"name": "ball", "material": {"color": [1, 0, 0]}, "field": )" +
                                    kBlob + R"(},
        {"name": "cutter",
         "shape": {"type": "box", "corner1": [-1, -20, -20], "corner2": [40, 20, 20]}}]}]})",
                                "cutaway.json");
    const CsgTracer tracer(traced_object(s.objects[0]), LipschitzMode::Local);
    TraceCounters work;
    const CsgHit h = tracer.first_hit({{30, 0.5, 0.5}, {-1, 0, 0}, 0, 0}, 0, 100, work);
    EXPECT_TRUE(h.hit);
    const SceneObject& face = face_object(s.objects[0], h.face);
    EXPECT_EQ(face.name, "cutter");
    return face.material.color;
  };
  const Vec3 with = cut_face_material(R"("cutaway_textures": true, )");
  EXPECT_EQ(with.x, 1);
  EXPECT_EQ(with.y, 0);
  const Vec3 grey = Material{}.color;
  for (const std::string key : {"", R"("cutaway_textures": false, )"}) {
    const Vec3 without = cut_face_material(key);
    EXPECT_EQ(without.x, grey.x);
    EXPECT_EQ(without.y, grey.y);
  }
}

// cutaway_textures follows POV-Ray's Determine_Textures through nested cutting CSGs (an
// intersection's face shows what all its other operands show), leaves a cutter with its own
// material and a union's parts alone, and refuses cut objects that show two materials.
TEST(Csg, CutawayTexturesNestAsInPovRay) {
  const auto load = [](const std::string& operands) {
    return parse_scene(R"({"camera": {"eye": [30, 0, 0], "target": [0, 0, 0]},
      "objects": [{"csg": "difference", "cutaway_textures": true, "operands": [)" +
                           operands + "]}]}",
                       "nest.json");
  };
  const std::string red =
      R"({"material": {"color": [1, 0, 0]}, "shape": {"type": "sphere", "radius": 3}})";
  const std::string bare = R"({"shape": {"type": "sphere", "radius": 2}})";
  const std::string blue =
      R"({"material": {"color": [0, 0, 1]}, "shape": {"type": "box", "corner1": [0, 0, 0],
          "corner2": [1, 1, 1]}})";
  const Scene s = load(R"({"csg": "intersection", "operands": [)" + red + ", " + bare + "]}, " +
                       R"({"csg": "difference", "operands": [)" + bare + ", " + bare + "]}, " +
                       blue + R"(, {"csg": "union", "operands": [)" + bare + ", " + bare + "]}");
  const auto& ops = s.objects[0].csg->operands;
  EXPECT_EQ(ops[0].csg->operands[1].material.color.x, 1);  // in the red sphere
  EXPECT_EQ(ops[1].csg->operands[0].material.color.x, 1);
  EXPECT_EQ(ops[1].csg->operands[1].material.color.x, 1);
  EXPECT_EQ(ops[2].material.color.z, 1);                     // its own
  EXPECT_EQ(ops[3].csg->operands[0].material.color.x, 0.8);  // the default
  EXPECT_THROW(load(R"({"csg": "union", "operands": [)" + red + ", " + blue + "]}, " + bare),
               SceneError);
  try {
    load(R"({"csg": "union", "operands": [)" + red + ", " + blue + "]}, " + bare);
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/objects/0/cutaway_textures"), std::string::npos)
        << e.what();
  }
}

// A red ball in front of a green CSG, inside the CSG's box (which a small box off to the side
// stretches towards the camera, so that Embree may well try the CSG first): each pixel's material
// is the surface it shows (a nearer hit keeps nothing of a farther CSG's face), with the objects
// in either order.
TEST(CsgRender, ANearerObjectKeepsItsOwnMaterialWhicheverEmbreeTriesFirst) {
  const std::string csg = R"({"csg": "union", "material": {"color": [0, 1, 0]}, "operands": [
      {"shape": {"type": "box", "corner1": [-6, -6, -6], "corner2": [0, 6, 6]}},
      {"shape": {"type": "sphere", "center": [0, 0, 0], "radius": 5}},
      {"shape": {"type": "box", "corner1": [15, 7, 7], "corner2": [20, 8, 8]}}]})";
  const std::string ball = R"({"material": {"color": [1, 0, 0]},
      "shape": {"type": "sphere", "center": [4, 0, 0], "radius": 1.5}})";
  const std::string dir = test::temp_dir("csg_render");
  for (const bool csg_first : {true, false}) {
    SCOPED_TRACE(csg_first ? "CSG first" : "ball first");
    const std::string scene = dir + "/scene.json", image = dir + "/scene.exr";
    std::ofstream(scene) << R"({"camera": {"eye": [30, 0, 0], "target": [0, 0, 0], "fov": 30},
      "objects": [)" << (csg_first ? csg + "," + ball : ball + "," + csg)
                         << "]}";
    ASSERT_EQ(test::run_softtrace("render " + scene +
                                  " -q --width 32 --height 24 --aov albedo -o " + image)
                  .status,
              0);
    const ImageFile f = read_image(image);
    const int r = f.channel("albedo.R"), g = f.channel("albedo.G");
    ASSERT_GE(r, 0);
    // The ball covers the frame's centre (it is nearer than the CSG's face at x = 5 there).
    EXPECT_EQ(f.at(16, 12, r), 1.0f);
    EXPECT_EQ(f.at(16, 12, g), 0.0f);
    int red = 0, green = 0;
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x) {
        red += f.at(x, y, r) == 1.0f && f.at(x, y, g) == 0.0f;
        green += f.at(x, y, r) == 0.0f && f.at(x, y, g) == 1.0f;
      }
    EXPECT_GT(red, 10);
    EXPECT_GT(green, 10);
  }
}

}  // namespace
}  // namespace softtrace

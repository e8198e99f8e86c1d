// Sphere tracing never silently skips a surface, checked on whole images: the hit mask of the
// normal render path (EmbreeScene::intersect for every pixel-centre camera ray) against a dense
// sampling march along the same rays. Every pixel the reference hits must be hit, no later than
// the reference's first inside sample; a pixel only the tracer hits (a sliver between samples)
// must have its hit point inside the solid. Scenes include grazing views, with the camera almost
// in the plane of a flat face, where the steps are shortest and a skip would be likeliest.
#include <gtest/gtest.h>

#include "render/camera.h"
#include "render/frame.h"
#include "scene_modes.h"

namespace softtrace {
namespace {

struct MaskCase {
  const char* name;
  const char* scene;
};

const MaskCase kCases[] = {
    {"fig12b",
     R"({"camera":{"eye":[62,-82,56],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","distance":{"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20}},
        {"type":"soft_object","distance":{"type":"lp_metric","radii":[30,30,12],"n":20}}]}}]})"},
    // Fig. 12(b) seen from just above the plane of the slab's flat top (z = 6, the 0.5 level).
    {"fig12b_grazing",
     R"({"camera":{"eye":[90,-20,6.3],"target":[0,0,6],"fov":40},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","distance":{"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20}},
        {"type":"soft_object","distance":{"type":"lp_metric","radii":[30,30,12],"n":20}}]}}]})"},
    // A constructive slab (|z| <= 4) whose top face is seen from 0.05 above its plane.
    {"slab_grazing",
     R"({"camera":{"eye":[22,3,4.05],"target":[0,0,3.2],"fov":60},"objects":[{"convention":"constructive",
        "field":{"type":"lp_metric","radii":[12,12,4],"n":30}}]})"},
    // Pinched superquadric (exponent below 1: no global Lipschitz bound) and a skew segment.
    {"pinched_segment",
     R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","distance":{"type":"superquadric","radii":[10,10,14],"n1":0.6,"n2":3}},
        {"type":"soft_object","distance":{"type":"segment","p0":[-12,0,6],"p1":[12,4,6],"radius":5}}]}}]})"},
    // [003] Fig. 9's bulge-eliminated crossing (m1 = 0.3), seen low over the hub: its box
    // Lipschitz bound comes from the spokes' Hessian bounds; globally it has none.
    {"wheel_hub_bulge",
     R"({"camera":{"eye":[1.2,-1.6,0.45],"target":[0,0,0.05],"fov":50},"objects":[{"convention":"zero",
        "bounds":[[-2.2,-2.2,-0.7],[2.2,2.2,0.7]],"field":{"type":"bt_union","base":"hyperellipsoid",
        "r":[0.8,0.8],"p":[2,2],"m":[0.3,1],"bulge_elimination":{"omega":0.05},"children":[
        {"type":"offset","children":[{"type":"segment","p0":[-1.85,0,0],"p1":[1.85,0,0],"radius":0.16}]},
        {"type":"offset","children":[{"type":"segment","p0":[0,-1.85,0],"p1":[0,1.85,0],"radius":0.16}]}]}}]})"},
};

class HitMask : public testing::TestWithParam<SceneMode> {};

TEST_P(HitMask, MatchesADenseReferenceMarch) {
  const Scene scene = parse_scene(kCases[std::get<0>(GetParam())].scene, "<test>");
  const TracedScene rt(scene, std::get<1>(GetParam()));
  // The reference marches the model tree, not the compiled program the tracer uses.
  const SceneObject& obj = scene.objects[0];
  const auto inside = [&](const Vec3& p) {
    return obj.inside_sign * (obj.field->value(p) - obj.iso) >= 0;
  };
  const Box& b = scene.objects[0].bounds;
  const int W = 40, H = 30, kSamples = 8000;
  const ViewCamera camera(scene.camera, W, H);
  int ref_hits = 0, tracer_only = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit hit = rt.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
      double t0 = 0, t1 = std::numeric_limits<double>::infinity();
      double ref = std::numeric_limits<double>::infinity();
      if (clip_to_box(ray, b, t0, t1))
        for (int i = 0; i <= kSamples && !std::isfinite(ref); ++i) {
          const double t = t0 + (t1 - t0) * i / kSamples;
          if (inside(ray.o + ray.d * t)) ref = t;
        }
      if (std::isfinite(ref)) {
        ++ref_hits;
        ASSERT_TRUE(hit.hit) << "pixel (" << x << ", " << y
                             << ") skipped the surface at t = " << ref;
        // Refinement stops within 1/1000 of the pixel footprint's radius (ray.cone per unit t).
        ASSERT_LE(hit.t, ref + 2e-3 * ray.cone * ref) << "pixel (" << x << ", " << y << ")";
      } else if (hit.hit) {
        ++tracer_only;
        // A give-up reports a hit where the surface may pass within a tolerance of the ray.
        if (hit.work.give_ups == 0) {
          EXPECT_TRUE(inside(ray.o + ray.d * hit.t)) << "pixel (" << x << ", " << y << ")";
        }
      }
    }
  EXPECT_GT(ref_hits, W * H / 20) << "the object should be in view";
  EXPECT_LE(tracer_only, W * H / 50) << "the tracer finds far more than the reference";
}

INSTANTIATE_TEST_SUITE_P(Scenes, HitMask, scene_modes(kCases),
                         [](const testing::TestParamInfo<SceneMode>& i) {
                           return scene_mode_name(kCases, i);
                         });

}  // namespace
}  // namespace softtrace

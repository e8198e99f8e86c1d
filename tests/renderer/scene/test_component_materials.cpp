// Per-component materials (docs/math.md "Blended materials"): the weights |s_i f_i(p)| / Σ|s_j f_j|
// a shaded point mixes its components' materials with, read from a scene.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/traced_objects.h"
#include "trace/tracer.h"

namespace softtrace {
namespace {

using Weights = std::vector<ComponentMaterials::Weight>;

// A ball of radius 2 at x = `x`, with `extra` keys (a material, a strength).
std::string ball(double x, const std::string& extra) {
  return R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[2,2,2],"n":2},)"
         R"("translate":[)" +
         std::to_string(x) + ",0,0]" + (extra.empty() ? "" : "," + extra) + "}";
}

Scene scene_of(const std::string& field) {
  return parse_scene(R"({"camera":{"eye":[10,-20,0],"target":[0,0,0]},"objects":[)"
                     R"({"material":{"color":[0.5,0.5,0.5]},"field":)" +
                         field + "}]}",
                     "s.json");
}

const std::string kRed = R"("material":{"color":[1,0,0],"phong":0.5})";
const std::string kBlue = R"("material":{"color":[0,0,1]})";

Weights weights_at(const Scene& s, const Vec3& p) {
  Weights w;
  s.objects[0].components->weights(p, w);
  return w;
}

// A component's own field value s f(p): the ball alone as an object's field (with bounds: a
// negative strength alone has no surface to bound).
double alone(const std::string& component, const Vec3& p) {
  return parse_scene(R"({"camera":{"eye":[10,-20,0],"target":[0,0,0]},"objects":[)"
                     R"({"bounds":[[-9,-9,-9],[9,9,9]],"field":)" +
                         component + "}]}",
                     "alone.json")
      .objects[0]
      .field->value(p);
}

TEST(ComponentMaterials, NoneGivenKeepsThePlainObject) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, "") + "," +
                           ball(1.5, "") + "]}");
  EXPECT_EQ(s.objects[0].components, nullptr);
}

// A blend without materials skips the walk that lists its components (plain(), the common case
// of a large cloud): a material under a nested blend alone must still be found, and a child that
// is no object still reported before the blend's other errors, as that walk reports it.
TEST(ComponentMaterials, AMaterialOnlyUnderANestedBlendIsFound) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, "") +
                           R"(,{"type":"soft_blend","children":[)" + ball(1.5, kBlue) + "]}]}");
  ASSERT_NE(s.objects[0].components, nullptr);
  EXPECT_EQ(s.objects[0].components->size(), 2);
}

TEST(ComponentMaterials, AChildThatIsNoObjectIsReportedFirst) {
  try {
    scene_of(R"({"type":"soft_blend","colour":1,"children":[)" + ball(0, "") + ",7]}");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "s.json: /objects/0/field/children/1: expected an object, got 7");
  }
}

TEST(ComponentMaterials, MaterialsAreReadWithTheirFinish) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) + "," +
                           ball(1.5, kBlue) + "]}");
  ASSERT_NE(s.objects[0].components, nullptr);
  const std::vector<Material>& m = s.objects[0].components->materials();
  ASSERT_EQ(m.size(), 3u);  // the object's, then the two components'
  EXPECT_EQ(m[0].color.x, 0.5);
  EXPECT_EQ(m[1].color.x, 1);
  EXPECT_EQ(m[1].phong, 0.5);
  EXPECT_EQ(m[2].color.z, 1);
}

TEST(ComponentMaterials, WhereOnlyOneIsNonZeroItsMaterialIsExact) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) + "," +
                           ball(1.5, kBlue) + "]}");
  // x = -3 is 1.5 from the red ball's centre and 4.5 from the blue one's (radius 2).
  const Weights w = weights_at(s, {-3, 0, 0});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].material, 1);
  EXPECT_EQ(w[0].weight, 1.0);
}

TEST(ComponentMaterials, TheMidpointOfTwoEqualComponentsIsTheMean) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) + "," +
                           ball(1.5, kBlue) + "]}");
  const Weights w = weights_at(s, {0, 0.3, 0.2});
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].material, 1);
  EXPECT_EQ(w[1].material, 2);
  EXPECT_EQ(w[0].weight, 0.5);
  EXPECT_EQ(w[1].weight, 0.5);
}

TEST(ComponentMaterials, WeightsFollowTheFieldValuesAndSumToOne) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) + "," +
                           ball(1.5, kBlue) + "]}");
  const Vec3 p{-0.4, 0.1, 0};
  const double red = alone(ball(-1.5, ""), p), blue = alone(ball(1.5, ""), p);
  ASSERT_GT(red, blue);
  const Weights w = weights_at(s, p);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_DOUBLE_EQ(w[0].weight, red / (red + blue));
  EXPECT_DOUBLE_EQ(w[0].weight + w[1].weight, 1.0);
}

TEST(ComponentMaterials, AComponentWithoutOneTakesTheObjects) {
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) + "," +
                           ball(1.5, "") + "]}");
  const Weights w = weights_at(s, {3, 0, 0});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].material, 0);
  EXPECT_EQ(w[0].weight, 1.0);
}

TEST(ComponentMaterials, ANegativeStrengthWeighsByItsMagnitude) {
  // POV-Ray takes |s f|: a dent's material shows where the dent is.
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) + "," +
                           ball(0.5, kBlue + R"(,"strength":-0.5)") + "]}");
  const Vec3 p{-0.5, 0, 0};
  const double red = alone(ball(-1.5, ""), p), dent = alone(ball(0.5, R"("strength":-0.5)"), p);
  ASSERT_LT(dent, 0);
  const Weights w = weights_at(s, p);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_DOUBLE_EQ(w[1].weight, -dent / (red - dent));
}

TEST(ComponentMaterials, NestedBlendsKeepTheirPlacement) {
  // The inner soft_blend moves its one ball by 10 along x: the ball's weight is 1 there, and
  // nothing at its unplaced position.
  const Scene s = scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed) +
                           R"(,{"type":"soft_blend","translate":[10,0,0],"children":[)" +
                           ball(0, kBlue) + "]}]}");
  Weights w = weights_at(s, {10.5, 0, 0});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].material, 2);
  EXPECT_EQ(w[0].weight, 1.0);
  w = weights_at(s, {0.4, 0, 0});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].material, 1);
}

// The renderer's way: the tracer's normal walk (the compiled gradient, or BlobSum's for a sum of
// polynomial blobs) leaves the components' values, whose weights are those of a walk of its own,
// and the normal is the plain one.
TEST(ComponentMaterials, TheNormalsWalkGivesTheSameWeights) {
  const std::string murakami = R"("potential":{"type":"murakami"})";
  for (const bool blob : {false, true}) {
    const std::string extra = blob ? "," + murakami : "";
    // BlobSum takes a flat sum; the compiled walk is tried with a nested, placed soft_blend.
    const std::string fourth =
        blob ? ball(0.5, kRed + extra)
             : R"({"type":"soft_blend","translate":[0,1,0],"children":[)" + ball(0.5, kRed) + "]}";
    const Scene s =
        scene_of(R"({"type":"soft_blend","children":[)" + ball(-1.5, kRed + extra) + "," +
                 ball(1.5, kBlue + extra) + "," + ball(0, murakami) + "," + fourth + "]}");
    const SceneObject& obj = s.objects[0];
    ASSERT_NE(obj.components, nullptr);
    ASSERT_EQ(obj.components->size(), 4);
    const ObjectTracer tracer(trace_target(obj), LipschitzMode::Local);
    EXPECT_EQ(tracer.blob_sum(), blob);
    std::vector<double> terms(4);
    int blended = 0;
    for (double x = -3.5; x <= 3.5; x += 0.25)
      for (double y = -2; y <= 3; y += 0.5) {
        const Vec3 p{x, y, 0.3};
        const Vec3 n = tracer.normal(p, terms.data()), plain = tracer.normal(p);
        EXPECT_EQ(n.x, plain.x);
        EXPECT_EQ(n.y, plain.y);
        EXPECT_EQ(n.z, plain.z);
        Weights fused;
        obj.components->weights(terms.data(), fused);
        const Weights own = weights_at(s, p);
        ASSERT_EQ(fused.size(), own.size()) << x << "," << y;
        for (size_t k = 0; k < own.size(); ++k) {
          EXPECT_EQ(fused[k].material, own[k].material);
          if (blob)  // BlobSum's polynomial rounds differently from the compiled potential
            EXPECT_NEAR(fused[k].weight, own[k].weight, 1e-14);
          else
            EXPECT_EQ(fused[k].weight, own[k].weight);
        }
        blended += own.size() > 1;
      }
    EXPECT_GT(blended, 20);
  }
}

}  // namespace
}  // namespace softtrace

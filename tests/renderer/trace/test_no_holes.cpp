// No holes: the hit mask of the normal render path (render_frame, whose beams certify each block
// of pixels' approach, and EmbreeScene::intersect for each pixel-centre camera ray on its own)
// against an exact one. Each scene is one object, a soft_blend of soft objects over n = 2
// lp_metrics whose supports do not overlap, so the solid is exactly a union of ellipsoids and
// every ray's first hit is a quadratic's root. With Murakami's potential the local mode traces the
// blobs as polynomials; with Blanc's, by segments, after the frame's beams. The cases are where a
// marcher with a shortest step or a loose bound goes wrong: a 1e-3 sphere beside a 1e3 one in the
// same object, a thin sheet and needles seen edge-on and end-on, and rays grazing a large sphere.
// A second suite (NoHolesMarch) takes solids with no closed-form hit (negative strengths, sheared
// capsules) against a dense reference march instead.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/frame.h"
#include "scene_modes.h"

namespace softtrace {
namespace {

// murakami (1 - r^2)^2 = 1/2 at r^2 = 1 - 1/sqrt(2): the soft convention's 0.5 level of a
// soft_object over lp_metric n = 2 with radii [a,b,c] is the ellipsoid kLevel * [a,b,c].
const double kLevel = std::sqrt(1 - 1 / std::sqrt(2.0));
// Blanc's is at d = 0.5 (docs/math.md §3.2): the same ellipsoid from radii kLevel / 0.5 times as
// large.
struct PotentialCase {
  const char* name;
  double scale;  // of the lp_metric's radii, for the same surface
};
const PotentialCase kPotentials[] = {{"murakami", 1}, {"blanc", kLevel / 0.5}};
constexpr double kInf = std::numeric_limits<double>::infinity();
// Rays whose closest approach to an ellipsoid, in the space where it is the unit sphere, is
// within this of 1 are left out as tangent. Rounding moves that distance by ~1e-15 (the field,
// the ray and the reference are all double), so this band is a billion times wider than any
// honest disagreement; yet in the image it is a ring ~1e-6 of the ellipsoid's apparent size
// wide around its outline, which no pixel of these 48x36 images should fall into by chance.
constexpr double kTangentBand = 1e-6;
constexpr int W = 48, H = 36;  // the images' size

struct Ellipsoid {
  // The Murakami lp_metric's radii (its support); the surface is kLevel * radii.
  Vec3 centre, radii;
};

struct HoleCase {
  const char* name;
  Camera camera;
  std::vector<Ellipsoid> parts;
};

// The centres 1089 apart: even Blanc's supports (radii 1082 and 0.0011) do not overlap.
const std::vector<Ellipsoid> kTinyAndHuge = {{{0, 0, 0}, {1e-3, 1e-3, 1e-3}},
                                             {{590, 915, 0}, {1e3, 1e3, 1e3}}};
const std::vector<Ellipsoid> kSheet = {{{0, 0, 0}, {10, 10, 0.01}}};
const std::vector<Ellipsoid> kNeedles = {{{0, 0, 0}, {0.01, 0.01, 10}},
                                         {{0.1, 0, 0}, {0.01, 0.01, 10}},
                                         {{0, 0.3, 0.05}, {10, 0.01, 0.01}}};
const std::vector<Ellipsoid> kUprightNeedles(kNeedles.begin(), kNeedles.begin() + 2);
const double kBigR = 1e3 * kLevel;  // the surface radius of the large sphere below
const std::vector<Ellipsoid> kBig = {{{0, 0, 0}, {1e3, 1e3, 1e3}}};

// Camera: eye, target, up, vertical fov in degrees.
const HoleCase kCases[] = {
    // The tiny sphere ~25 pixels across, the huge one filling the right of the picture.
    {"tiny_near", {{0, -0.003, 0}, {0, 0, 0}, {0, 0, 1}, 30}, kTinyAndHuge},
    // The same from 8 times farther: the tiny sphere covers a handful of pixels.
    {"tiny_far", {{0, -0.025, 0}, {1e-4, 0, 6e-5}, {0, 0, 1}, 30}, kTinyAndHuge},
    {"sheet_oblique", {{12, -9, 7}, {0, 0, 0}, {0, 0, 1}, 50}, kSheet},
    // About 1 degree above the sheet's plane.
    {"sheet_grazing", {{19.7, -3.4, 0.35}, {0, 0, 0}, {0, 0, 1}, 10}, kSheet},
    // Tilting `up` slants the needles across the pixel columns.
    {"needles_across", {{0, -1.2, 0}, {0.05, 0, 0}, {0.1, 0, 1}, 30}, kNeedles},
    // About 2 degrees off the vertical needles' axis.
    {"needles_end_on", {{0.3, 0.2, 12}, {0, 0, 0}, {0, 1, 0}, 2}, kUprightNeedles},
    // The eye 0.05 above the top of a sphere of radius 541: the horizon at grazing incidence.
    {"sphere_horizon", {{0, 0, kBigR + 0.05}, {0, 100, kBigR - 3}, {0, 0, 1}, 30}, kBig},
    // Its top outline from afar, the eye 0.5 above the tangent plane.
    {"sphere_outline", {{0, -2000, kBigR + 0.5}, {0, 0, kBigR}, {0, 0, 1}, 1}, kBig},
};

std::string json_num(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.17g", v);
  return s;
}

std::string json_vec(const Vec3& v) {
  return "[" + json_num(v.x) + "," + json_num(v.y) + "," + json_num(v.z) + "]";
}

std::string scene_json(const HoleCase& c, const PotentialCase& pot) {
  std::string parts;
  for (const Ellipsoid& e : c.parts)
    parts += std::string(parts.empty() ? "" : ",") + R"({"type":"soft_object","translate":)" +
             json_vec(e.centre) + R"(,"potential":{"type":")" + pot.name + R"("},)" +
             R"("distance":{"type":"lp_metric","n":2,"radii":)" + json_vec(e.radii * pot.scale) +
             "}}";
  const std::string field =
      c.parts.size() == 1 ? parts : R"({"type":"soft_blend","children":[)" + parts + "]}";
  return R"({"camera":{"eye":)" + json_vec(c.camera.eye) + R"(,"target":)" +
         json_vec(c.camera.target) + R"(,"up":)" + json_vec(c.camera.up) + R"(,"fov":)" +
         json_num(c.camera.fov) + R"(},"objects":[{"field":)" + field + "}]}";
}

struct RefHit {
  double t = kInf;  // the first hit at t >= 0, or inf
  bool tangent = false;
};

// The offset p from the ellipsoid's centre in the space where its surface is the unit sphere.
Vec3 unit_space(const Ellipsoid& e, const Vec3& p) {
  const Vec3 s = e.radii * kLevel;
  return {p.x / s.x, p.y / s.y, p.z / s.z};
}

// There the ray is u + t v; its closest approach to the centre, m, is taken from the
// perpendicular component so that it is accurate near 1.
RefHit ellipsoid_hit(const Ray& ray, const Ellipsoid& e) {
  const Vec3 u = unit_space(e, ray.o - e.centre), v = unit_space(e, ray.d);
  const double tc = -dot(u, v) / dot(v, v);
  if (tc <= 0) return {};  // moving away from an eye outside: no hit, far from tangent
  const double m = length(u + v * tc);
  if (std::abs(m - 1) < kTangentBand) return {kInf, true};
  if (m > 1) return {};
  return {tc - std::sqrt((1 - m) * (1 + m)) / length(v), false};
}

// Every pixel-centre ray's first hit, from `traced` (x, y -> t, inf for none), against the
// ellipsoids' exact one.
template <class Traced>
void check_hit_mask(const HoleCase& c, const SceneObject& obj, const ViewCamera& camera,
                    const char* path, const Traced& traced) {
  // A pixel's width at unit depth; the t tolerance is 1e-3 of it at the hit's depth.
  const double footprint = 2 * std::tan(0.5 * c.camera.fov * M_PI / 180) / H;
  int hits = 0, misses = 0, tangent = 0;  // the reference's, over the pixels not left out
  int missed = 0, extra = 0, off = 0;     // hits the tracer missed, made up, or put elsewhere
  std::vector<int> seen(c.parts.size(), 0);
  double worst = 0, worst_ratio = 0;  // |t - t_ref|, and over its tolerance
  std::string first;                  // the first wrong pixel
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      RefHit ref;
      int part = -1;
      for (size_t i = 0; i < c.parts.size(); ++i) {
        const RefHit h = ellipsoid_hit(ray, c.parts[i]);
        ref.tangent |= h.tangent;
        if (h.t < ref.t) ref.t = h.t, part = int(i);
      }
      if (ref.tangent) {
        ++tangent;
        continue;
      }
      const double t = traced(x, y);
      const bool hit = std::isfinite(t);
      const std::string where = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): ";
      if (!std::isfinite(ref.t)) {
        ++misses;
        if (hit && extra++ + missed + off == 0)
          first = where + "hit at t = " + std::to_string(t) + " where there is nothing";
        continue;
      }
      ++hits;
      ++seen[part];
      // The reference is the field's level: an independent check of kLevel and the placement.
      ASSERT_NEAR(obj.field->value(ray.o + ray.d * ref.t), obj.iso, 1e-9) << where;
      if (!hit) {
        if (extra + missed++ + off == 0)
          first = where + "missed ellipsoid " + std::to_string(part) +
                  " at t = " + std::to_string(ref.t);
        continue;
      }
      // (The frame keeps t as a float: 6e-8 of t, far inside this.)
      const double err = std::abs(t - ref.t), tol = 1e-3 * footprint * ref.t + 1e-12;
      worst = std::max(worst, err);
      worst_ratio = std::max(worst_ratio, err / tol);
      if (err > tol && extra + missed + off++ == 0)
        first = where + "hit at t = " + std::to_string(t) + ", not at ellipsoid " +
                std::to_string(part) + "'s t = " + std::to_string(ref.t);
    }
  std::printf(
      "%s, %s: %d hits, %d misses, %d tangent; %d missed, %d extra, %d off; "
      "worst |t - t_ref| %.3g (%.3g of the tolerance)\n",
      c.name, path, hits, misses, tangent, missed, extra, off, worst, worst_ratio);
  EXPECT_EQ(missed + extra + off, 0)
      << path << ": " << missed << " hits missed, " << extra << " made up, " << off
      << " off by more than the tolerance (worst " << worst << "); the first, " << first;
  EXPECT_LE(tangent, W * H / 100) << "too many pixels left out as tangent";
  EXPECT_GE(hits, W * H / 100) << "the object should be in view";
  EXPECT_GE(misses, W * H / 100) << "the background should be in view";
  for (size_t i = 0; i < seen.size(); ++i)
    EXPECT_GT(seen[i], 0) << "ellipsoid " << i << " is the first hit of no pixel";
}

class NoHoles : public testing::TestWithParam<SceneMode> {};

TEST_P(NoHoles, HitMaskIsExact) {
  const HoleCase& c = kCases[std::get<0>(GetParam())];
  for (const PotentialCase& pot : kPotentials) {
    SCOPED_TRACE(pot.name);
    Scene scene = parse_scene(scene_json(c, pot), "<test>");
    scene.image.spp = 1;  // the pixel's centre
    const TracedScene rt(scene, std::get<1>(GetParam()));
    const SceneObject& obj = scene.objects[0];
    for (const Ellipsoid& e : c.parts)  // which ellipsoid_hit assumes
      ASSERT_GT(length(unit_space(e, c.camera.eye - e.centre)), 1 + kTangentBand)
          << "the eye must be outside every ellipsoid";
    const ViewCamera camera(scene.camera, W, H);
    // A pixel-centre ray's first hit (t, or inf where it hits nothing), on its own and in the
    // whole frame (beams and all).
    const auto ray_alone = [&](int x, int y) {
      const TraceHit hit = rt.embree.intersect(camera.generate(x + 0.5, y + 0.5), 0, kInf);
      return hit.hit ? hit.t : kInf;
    };
    Film film(W, H);
    ASSERT_TRUE(render_frame(scene, rt, RenderOptions{}, film, nullptr, nullptr));
    const auto in_frame = [&](int x, int y) { return double(film.depth[size_t(y) * W + x]); };
    check_hit_mask(c, obj, camera, (std::string(pot.name) + ", alone").c_str(), ray_alone);
    check_hit_mask(c, obj, camera, (std::string(pot.name) + ", frame").c_str(), in_frame);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, NoHoles, scene_modes(kCases),
                         [](const testing::TestParamInfo<SceneMode>& i) {
                           return scene_mode_name(kCases, i);
                         });

// Solids with no closed-form first hit, against a dense sampling march of the model tree along
// the same pixel-centre rays: a large blob with a small hole punched into it by a negative
// strength, thin capsules sheared by a matrix (an affine placement), a chain of capsules, a groove
// cut by a negative capsule, and a thin capsule seen end-on and along its side (all on the
// polynomial blob path in the local mode), each also seen at grazing incidence. No pixel may
// differ: every reference hit is hit, no later than the reference's first inside sample, and every
// hit the reference misses (a sliver between its samples) lies inside the solid.
struct MarchCase {
  const char* name;
  Camera camera;
  const char* field;
};

const char* const kHoleField = R"({"type":"soft_blend","children":[
    {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"lp_metric","radii":[4,4,4],"n":2}},
    {"type":"soft_object","potential":{"type":"murakami"},"strength":-1.5,"translate":[2.1,0.3,0],
     "distance":{"type":"lp_metric","radii":[0.9,0.9,0.9],"n":2}}]})";
const char* const kShearedField = R"({"type":"soft_blend","children":[
    {"type":"soft_object","potential":{"type":"murakami"},"matrix":[[1,0.9,0,0],[0,0.12,0,0],[0.3,0,1,0]],
     "distance":{"type":"segment","p0":[-3,0,0],"p1":[3,0,0],"radius":1}},
    {"type":"soft_object","potential":{"type":"cubic"},"strength":1.4,"matrix":[[0.1,0,0,1],[0.5,1,0,0.5],[0,0.6,0.08,0.4]],
     "distance":{"type":"segment","p0":[0,-3,0],"p1":[0,3,0],"radius":1}}]})";

// Flattened and sheared ellipsoids (scale after rotate, a matrix), one of them negative: the
// polynomial blob path reads their affine frames.
const char* const kShearedBlobsField = R"({"type":"soft_blend","children":[
    {"type":"soft_object","potential":{"type":"murakami"},"scale":[3,1,0.15],"rotate":{"axis":[1,1,0],"deg":30},
     "distance":{"type":"lp_metric","radii":[1,1,1],"n":2}},
    {"type":"soft_object","potential":{"type":"cubic"},"strength":1.8,"matrix":[[0.3,1.5,0,1.2],[0,0.4,0,0.5],[0,0.9,0.1,0]],
     "distance":{"type":"lp_metric","radii":[1,1,1],"n":2}},
    {"type":"soft_object","potential":{"type":"wyvill"},"strength":-1,"scale":[0.8,0.8,0.8],"translate":[0.6,0.2,0],
     "distance":{"type":"lp_metric","radii":[1,1,1],"n":2}}]})";

// Capsules (segments) on the polynomial path: a chain of them with a ball at a joint and a
// point skeleton (a zero-length segment) at its end, in each potential.
const char* const kCapsuleChainField = R"({"type":"soft_blend","children":[
    {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"segment","p0":[-6,0,0],"p1":[-2,2,0],"radius":1.6}},
    {"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"segment","p0":[-2,2,0],"p1":[2,0,1],"radius":1.6}},
    {"type":"soft_object","potential":{"type":"cubic"},"strength":1.5,"distance":{"type":"segment","p0":[2,0,1],"p1":[6,2,0],"radius":1.2}},
    {"type":"soft_object","potential":{"type":"murakami"},"strength":0.8,"translate":[-2,2,0],
     "distance":{"type":"lp_metric","radii":[2,2,2],"n":2}},
    {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"segment","p0":[6,2,0],"p1":[6,2,0],"radius":2}}]})";
// A negative capsule cutting a groove through a ball, off its centre.
const char* const kCapsuleCutField = R"({"type":"soft_blend","children":[
    {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"lp_metric","radii":[4,4,4],"n":2}},
    {"type":"soft_object","potential":{"type":"murakami"},"strength":-1.5,
     "distance":{"type":"segment","p0":[-5,0.5,1.4],"p1":[5,0.5,1.4],"radius":1.3}}]})";
// A thin capsule along x (its surface radius 0.4 kLevel = 0.216) beside a fatter one.
const char* const kCapsuleAxisField = R"({"type":"soft_blend","children":[
    {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"segment","p0":[-5,0,0],"p1":[5,0,0],"radius":0.4}},
    {"type":"soft_object","potential":{"type":"wyvill"},"distance":{"type":"segment","p0":[-3,1.5,0],"p1":[3,1.5,0],"radius":1}}]})";

// Camera: eye, target, up, vertical fov in degrees.
const MarchCase kMarchCases[] = {
    {"hole", {{9, -4, 3}, {2, 0, 0}, {0, 0, 1}, 40}, kHoleField},
    // Just above the tangent plane at the hole's rim, looking across it.
    {"hole_grazing", {{2.3, -7, 0.9}, {2.0, 0, 0.75}, {0, 0, 1}, 20}, kHoleField},
    {"sheared_capsules", {{2, -9, 5}, {0.5, 0, 0.3}, {0, 0, 1}, 40}, kShearedField},
    // Nearly in the plane of the thin sheared sheet (its normal is about y).
    {"sheared_capsules_grazing", {{1, -7, 0.25}, {0, 0, 0}, {0, 0, 1}, 30}, kShearedField},
    {"sheared_blobs", {{3, -6, 4}, {0.5, 0, 0}, {0, 0, 1}, 40}, kShearedBlobsField},
    // Almost edge-on to the flattened one's plane.
    {"sheared_blobs_grazing", {{5, -5, 0.6}, {0, 0, 0}, {0, 0, 1}, 35}, kShearedBlobsField},
    {"capsule_chain", {{3, -14, 8}, {0, 1, 0.3}, {0, 0, 1}, 50}, kCapsuleChainField},
    {"capsule_cut", {{7, -6, 6}, {0, 0, 0.5}, {0, 0, 1}, 45}, kCapsuleCutField},
    // Down the groove, along the negative capsule's axis.
    {"capsule_cut_along_axis", {{-14, 0.5, 1.6}, {0, 0.5, 1.4}, {0, 0, 1}, 25}, kCapsuleCutField},
    // End-on: about 0.1 degree off the thin capsule's axis.
    {"capsule_end_on", {{-15, 0.02, 0.01}, {0, 0, 0}, {0, 0, 1}, 6}, kCapsuleAxisField},
    // Along the thin capsule's top line: its rays graze the cylinder from end to end.
    {"capsule_axis_grazing", {{-14, 0, 0.2165}, {0, 0, 0.2165}, {0, 0, 1}, 4}, kCapsuleAxisField},
};

std::string march_scene_json(const MarchCase& c) {
  return R"({"camera":{"eye":)" + json_vec(c.camera.eye) + R"(,"target":)" +
         json_vec(c.camera.target) + R"(,"up":)" + json_vec(c.camera.up) + R"(,"fov":)" +
         json_num(c.camera.fov) + R"(},"objects":[{"field":)" + c.field + "}]}";
}

class NoHolesMarch : public testing::TestWithParam<SceneMode> {};

TEST_P(NoHolesMarch, HitMaskMatchesADenseReferenceMarch) {
  const Scene scene = parse_scene(march_scene_json(kMarchCases[std::get<0>(GetParam())]), "<test>");
  const TracedScene rt(scene, std::get<1>(GetParam()));
  const SceneObject& obj = scene.objects[0];
  const auto inside = [&](const Vec3& p) {
    return obj.inside_sign * (obj.field->value(p) - obj.iso) >= 0;
  };
  const ViewCamera camera(scene.camera, W, H);
  constexpr int kSamples = 8000;
  int ref_hits = 0, ref_misses = 0, differ = 0;
  std::string first;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit hit = rt.embree.intersect(ray, 0, kInf);
      double t0 = 0, t1 = kInf, ref = kInf;
      if (clip_to_box(ray, obj.bounds, t0, t1))
        for (int i = 0; i <= kSamples && !std::isfinite(ref); ++i) {
          const double t = t0 + (t1 - t0) * i / kSamples;
          if (inside(ray.o + ray.d * t)) ref = t;
        }
      const std::string where = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
      bool bad = false;
      if (std::isfinite(ref)) {
        ++ref_hits;
        bad = !hit.hit || hit.t > ref + 2e-3 * ray.cone * ref;
      } else {
        ++ref_misses;
        bad = hit.hit && hit.work.give_ups == 0 && !inside(ray.o + ray.d * hit.t);
      }
      if (bad && differ++ == 0)
        first = where + ": reference t = " + std::to_string(ref) + ", tracer " +
                (hit.hit ? "t = " + std::to_string(hit.t) : std::string("none"));
    }
  EXPECT_EQ(differ, 0) << differ << " pixels differ from the reference march; the first, " << first;
  EXPECT_GE(ref_hits, W * H / 20) << "the object should be in view";
  EXPECT_GE(ref_misses, W * H / 20) << "the background should be in view";
}

INSTANTIATE_TEST_SUITE_P(Scenes, NoHolesMarch, scene_modes(kMarchCases),
                         [](const testing::TestParamInfo<SceneMode>& i) {
                           return scene_mode_name(kMarchCases, i);
                         });

}  // namespace
}  // namespace softtrace

// Sweep cases for POV-Ray's blob components (see sweep.h): soft objects with a strength (negative
// ones subtract), affine placement (scale, matrix) and the cubic potential.
#include "sweep.h"

namespace softtrace::test {
namespace {

#define BIG \
  R"({"type":"soft_object","potential":{"type":"murakami"},"strength":2,"distance":{"type":"lp_metric","radii":[2,1.6,1.8],"n":2}})"
#define HOLE \
  R"({"type":"soft_object","potential":{"type":"murakami"},"strength":-1.5,"translate":[0.8,0.2,0],"distance":{"type":"lp_metric","radii":[0.7,0.7,0.7],"n":2}})"
#define SHEARED \
  R"({"type":"soft_object","potential":{"type":"cubic"},"matrix":[[1,0.8,0,0.1],[0,0.3,0,-0.2],[0.2,0,0.5,0.3]],"distance":{"type":"segment","p0":[-1,0,0],"p1":[1,0,0],"radius":1}})"

const SweepCase kBlobCases[] = {
    {"strength_positive",
     R"({"type":"soft_object","strength":2.5,"potential":{"type":"wyvill"},
         "distance":{"type":"lp_metric","radii":[1,1.2,0.9],"n":2}})",
     kUnit},
    // {s f <= -tiny} is the support of f: a negative term's region below 0.
    {"strength_negative",
     R"({"type":"soft_object","strength":-0.7,"translate":[0.2,0,0],
         "distance":{"type":"lp_metric","radii":[1,1.2,0.9],"n":3}})",
     kUnit, Convention::Soft, -1e-300, Side::Below},
    {"strength_negative_transformed",
     R"({"type":"soft_object","strength":-3,"radii":{"type":"T_n","w1":1.6,"w2":0.7},
         "distance":{"type":"lp_metric","radii":[1,0.8,1.1],"n":2}})",
     kUnit, Convention::Soft, -1e-300, Side::Below},
    {"soft_blend_hole", R"({"type":"soft_blend","children":[)" BIG "," HOLE "]}", kWide},
    {"soft_blend_hole_level", R"({"type":"soft_blend","children":[)" BIG "," HOLE "]}", kWide,
     Convention::Soft, 0.5, Side::Above},
    {"soft_blend_single", R"({"type":"soft_blend","children":[)" SHEARED "]}", kUnit},
    {"min_with_hole", R"({"type":"min","children":[)" BIG "," HOLE "]}", kWide},
    {"max_with_hole", R"({"type":"max","children":[)" BIG "," HOLE "]}", kWide},
    {"perlin_union_strong", R"({"type":"perlin_union","children":[)" BIG "," SHEARED "]}", kWide},
    {"scale_union_strong",
     R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1,"children":[)" BIG "," SHEARED "]}", kWide},
    {"ricci_union_strong", R"({"type":"ricci_union","n":2,"children":[)" BIG "," SHEARED "]}",
     kWide},
    {"cubic",
     R"({"type":"soft_object","potential":{"type":"cubic"},
         "distance":{"type":"lp_metric","radii":[1,0.8,1.2],"n":2}})",
     kUnit},
    {"scaled_sphere",
     R"({"type":"soft_object","potential":{"type":"murakami"},"scale":[2,0.5,-1.2],
         "rotate":{"axis":[1,2,0],"deg":40},"translate":[0.3,0,0.1],
         "distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})",
     kWide},
    {"scaled_distance", R"({"type":"lp_metric","radii":[1,1,1],"n":4,"scale":[0.5,1.5,1]})", kUnit,
     Convention::Soft, 1.0, Side::Below},
    {"sheared_capsule", SHEARED, kUnit},
    {"sheared_blend",
     R"({"type":"soft_blend","matrix":[[0.5,0.5,0,0],[0,1,0.4,0],[0,0,2,0.5]],"children":[)" BIG
     "," HOLE "," SHEARED "]}",
     kWide},
};

SOFTTRACE_SWEEP_FAMILY(Blobs, kBlobCases);

#undef BIG
#undef HOLE
#undef SHEARED

}  // namespace
}  // namespace softtrace::test

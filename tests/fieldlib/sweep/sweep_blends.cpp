// Sweep cases for the set blends (see sweep.h): soft objects in the soft convention; Ricci, scale,
// min/max and complement also on distance functions in the constructive convention.
#include <limits>

#include "sweep.h"

namespace softtrace::test {
namespace {

const Box kDom({-2, -2, -2}, {2, 2, 2});
const double kNone = std::numeric_limits<double>::quiet_NaN();

#define SOFT_A \
  R"({"type":"soft_object","translate":[-0.4,0,0],"distance":{"type":"lp_metric","radii":[1,0.8,1.1],"n":2}})"
#define SOFT_B \
  R"({"type":"soft_object","translate":[0.5,0.2,0],"distance":{"type":"superquadric","radii":[0.9,1.2,0.8],"n1":2,"n2":4}})"
#define SOFT_C \
  R"({"type":"soft_object","translate":[0,-0.3,0.4],"potential":{"type":"wyvill"},"distance":{"type":"lp_metric","radii":[0.7,0.7,1.3],"n":3}})"
// Soft objects whose radii are transformed: their global ranges and bounds come from bounds over
// an unbounded box, which an infinite distance once turned into NaN (and [1, 1]).
#define SOFT_TN \
  R"({"type":"soft_object","translate":[0.3,0,0.2],"distance":{"type":"lp_metric","radii":[1,0.8,1.1],"n":2},"radii":{"type":"T_n","w1":1.6,"w2":0.7}})"
#define SOFT_TL \
  R"({"type":"soft_object","translate":[-0.3,0.2,0],"distance":{"type":"superquadric","radii":[0.9,1.2,0.8],"n1":2,"n2":4},"radii":{"type":"T_l","w1":0.6}})"
#define DIST_A R"({"type":"lp_metric","translate":[-0.4,0,0],"radii":[1,0.8,1.1],"n":2})"
#define DIST_B \
  R"({"type":"superquadric","translate":[0.5,0.2,0.1],"radii":[0.9,1.2,0.8],"n1":2,"n2":4})"
#define ZERO(d) R"({"type":"offset","children":[)" d "]}"
#define DIST_FAR R"({"type":"lp_metric","translate":[0.3,3,0],"radii":[1,1.5,1],"n":2})"

const SweepCase kBlendCases[] = {
    {"perlin_union", R"({"type":"perlin_union","children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}",
     kDom},
    {"perlin_intersection",
     R"({"type":"perlin_intersection","children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}", kDom},
    {"perlin_difference",
     R"({"type":"perlin_difference","children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}", kDom},
    {"perlin_union_transformed", R"({"type":"perlin_union","children":[)" SOFT_TN "," SOFT_TL "]}",
     kDom},
    {"ricci_soft_union_transformed",
     R"({"type":"ricci_union","n":2,"children":[)" SOFT_TN "," SOFT_TL "]}", kDom},
    {"ricci_soft_union_n2", R"({"type":"ricci_union","n":2,"children":[)" SOFT_A "," SOFT_B "]}",
     kDom},
    {"ricci_soft_union_n0_7",
     R"({"type":"ricci_union","n":0.7,"children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}", kDom},
    {"ricci_soft_intersection",
     R"({"type":"ricci_intersection","n":4,"children":[)" SOFT_A "," SOFT_B "]}", kDom},
    {"ricci_soft_difference",
     R"({"type":"ricci_difference","n":3,"children":[)" SOFT_A "," SOFT_B "]}", kDom},
    {"scale_soft_union",
     R"({"type":"scale_union","r1":0.6,"r2":0.4,"p":0.1,"children":[)" SOFT_A "," SOFT_B "]}",
     kDom},
    {"scale_soft_intersection",
     R"({"type":"scale_intersection","r1":0.5,"r2":0.9,"p":-0.3,"children":[)" SOFT_A "," SOFT_B
     "]}",
     kDom},
    {"min_soft", R"({"type":"min","children":[)" SOFT_A "," SOFT_B "]}", kDom},
    {"max_soft", R"({"type":"max","children":[)" SOFT_A "," SOFT_B "," SOFT_C "]}", kDom},
    {"complement_soft", R"({"type":"complement","children":[)" SOFT_A "]}", kDom, Convention::Soft,
     kNone},
    {"ricci_cg_union", R"({"type":"ricci_union","n":4,"children":[)" DIST_A "," DIST_B "]}", kDom,
     Convention::Constructive, 1.0, Side::Below},
    {"ricci_cg_intersection",
     R"({"type":"ricci_intersection","n":2.5,"children":[)" DIST_A "," DIST_B "]}", kDom,
     Convention::Constructive, 1.0, Side::Below},
    {"ricci_cg_difference",
     R"({"type":"ricci_difference","n":6,"children":[)" DIST_A "," DIST_FAR "]}", kDom,
     Convention::Constructive, 1.0, Side::Below},
    {"scale_cg_union_ellipse",
     R"({"type":"scale_union","r1":0.5,"r2":0.8,"p":0.2,"children":[)" DIST_A "," DIST_B "]}", kDom,
     Convention::Constructive, 1.0, Side::Below},
    {"scale_cg_union_hyperbola",
     R"({"type":"scale_union","r1":0.7,"r2":0.4,"p":-1.5,"children":[)" DIST_A "," DIST_B "]}",
     kDom, Convention::Constructive, 1.0, Side::Below},
    {"scale_cg_intersection",
     R"({"type":"scale_intersection","r1":0.5,"r2":0.3,"p":0.05,"children":[)" DIST_A "," DIST_B
     "]}",
     kDom, Convention::Constructive, 1.0, Side::Below},
    {"scale_cg_intersection_neg_p",
     R"({"type":"scale_intersection","r1":0.4,"r2":0.6,"p":-0.8,"children":[)" DIST_A "," DIST_B
     "]}",
     kDom, Convention::Constructive, 1.0, Side::Below},
    {"complement_cg", R"({"type":"complement","children":[)" DIST_FAR "]}", kDom,
     Convention::Constructive, 0.8, Side::Above},
    // Zero-convention blends take zero-surface functions: offsets d - 1 of the distances.
    {"min_zero", R"({"type":"min","children":[)" ZERO(DIST_A) "," ZERO(DIST_B) "]}", kDom,
     Convention::Zero, 0.0, Side::Below},
    {"max_zero", R"({"type":"max","children":[)" ZERO(DIST_A) "," ZERO(DIST_B) "]}", kDom,
     Convention::Zero, 0.0, Side::Below},
    {"complement_zero", R"({"type":"complement","children":[)" ZERO(DIST_A) "]}", kDom,
     Convention::Zero, 0.0, Side::Above},
};

SOFTTRACE_SWEEP_FAMILY(Blends, kBlendCases);

#undef SOFT_A
#undef SOFT_B
#undef SOFT_C
#undef SOFT_TN
#undef SOFT_TL
#undef DIST_A
#undef DIST_B
#undef ZERO
#undef DIST_FAR

}  // namespace
}  // namespace softtrace::test

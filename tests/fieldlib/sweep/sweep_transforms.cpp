// Sweep cases for soft objects with radius transforms (see sweep.h): every transform, on
// ray-linear distances, with modulation/contour surfaces about the same centre.
#include "sweep.h"

namespace softtrace::test {
namespace {

const Box kTransformBox({-2.5, -2.5, -2.5}, {2.5, 2.5, 2.5});

#define SPHERE R"({"type":"lp_metric","radii":[1,0.8,1.2],"n":2})"
#define BAR R"({"type":"superquadric","radii":[1,1,1.3],"n1":2,"n2":6})"

const SweepCase kTransformCases[] = {
    {"T_n_wide",
     R"({"type":"soft_object","distance":)" SPHERE R"(,"radii":{"type":"T_n","w1":1.6,"w2":0.7}})",
     kTransformBox},
    {"T_n_narrow",
     R"({"type":"soft_object","distance":)" BAR R"(,"radii":{"type":"T_n","w1":0.4,"w2":0.8}})",
     kUnit},
    {"T_n_wyvill",
     R"({"type":"soft_object","potential":{"type":"wyvill"},"distance":)" SPHERE
     R"(,"radii":{"type":"T_n","w1":0.7,"w2":1}})",
     kUnit},
    {"T_l_k_above_1",
     R"({"type":"soft_object","distance":)" SPHERE R"(,"radii":{"type":"T_l","w1":0.6}})", kUnit},
    {"T_l_k_below_1",
     R"({"type":"soft_object","distance":)" BAR R"(,"radii":{"type":"T_l","w1":2}})",
     kTransformBox},
    {"T_r", R"({"type":"soft_object","distance":)" SPHERE R"(,"radii":{"type":"T_r","w2":0.4}})",
     kUnit},
    {"T_an",
     R"({"type":"soft_object","distance":)" SPHERE
     R"(,"radii":{"type":"T_an","modulation":
                 {"type":"superquadric","radii":[2.2,1.8,1.6],"n1":1,"n2":3}}})",
     kTransformBox},
    {"T_an_thin",
     R"({"type":"soft_object","distance":)" BAR
     R"(,"radii":{"type":"T_an","modulation":
                      {"type":"lp_metric","radii":[1.8,2.2,2],"n":1.5}}})",
     kTransformBox},
    // The modulation close outside d (w ~ 0.017 on five sides, 002 Fig. 3's cylinders): T_n's
    // steep linear branch, d and f rising together.
    {"T_an_close",
     R"({"type":"soft_object","distance":{"type":"superelliptic_cylinder","radii":[1,1,1],"n":8,
         "half_length":1.5},"radii":{"type":"T_an","modulation":{"type":"superelliptic_cylinder",
         "radii":[1,1,1],"n":8,"half_length":1.5,"t":[1.0166666666666667,1.0166666666666667,2,
         1.0166666666666667,1.0166666666666667,1.0166666666666667]}}})",
     kTransformBox},
    {"T_al",
     R"({"type":"soft_object","distance":)" SPHERE
     R"(,"radii":{"type":"T_al","modulation":
                 {"type":"lp_metric","radii":[1.8,1.2,2.4],"n":3}}})",
     kTransformBox},
    {"T_sn",
     R"({"type":"soft_object","distance":)" BAR
     R"(,"radii":{"type":"T_sn","modulation":
                 {"type":"lp_metric","radii":[0.7,0.8,0.6],"n":3}}})",
     kUnit},
    {"T_sr",
     R"({"type":"soft_object","distance":)" SPHERE
     R"(,"radii":{"type":"T_sr","modulation":
                 {"type":"superquadric","radii":[0.6,0.5,0.9],"n1":1.5,"n2":2}}})",
     kUnit},
    {"contour",
     R"({"type":"soft_object","distance":)" SPHERE
     R"(,"radii":{"type":"contour","contour":
                    {"type":"lp_metric","radii":[1.4,1.1,2],"n":4}}})",
     kTransformBox},
    {"contour_pinched_placed",
     R"({"type":"soft_object","translate":[0.2,0,-0.1],"distance":)" BAR
     R"(,"radii":{"type":"contour","w_min":0.01,"contour":
         {"type":"superquadric","radii":[2,2,2.6],"n1":0.6,"n2":4}}})",
     kTransformBox},
};

SOFTTRACE_SWEEP_FAMILY(Transforms, kTransformCases);

#undef SPHERE
#undef BAR

}  // namespace
}  // namespace softtrace::test

// Sweep cases for the foundation's nodes (see sweep.h).
#include "sweep.h"

namespace softtrace::test {
namespace {

const Box kFig12({-40, -40, -30}, {40, 40, 30});

const SweepCase kFoundationCases[] = {
    {"lp_metric_n2", R"({"type":"lp_metric","radii":[1,2,0.5],"n":2})", kUnit, Convention::Soft,
     1.0, Side::Below},
    {"lp_metric_n2_cylinder_placed",
     R"({"type":"lp_metric","radii":[0.4,0.3,3],"n":2,"translate":[0.1,0.2,0],
         "rotate":{"axis":[1,1,0],"deg":60}})",
     kUnit, Convention::Soft, 1.0, Side::Below},
    {"lp_metric_n1", R"({"type":"lp_metric","radii":[1,2,0.5],"n":1})", kUnit, Convention::Soft,
     1.0, Side::Below},
    {"lp_metric_n1_5", R"({"type":"lp_metric","radii":[1,0.7,1.3],"n":1.5})", kUnit,
     Convention::Soft, 0.5, Side::Below},
    {"lp_metric_n20", R"({"type":"lp_metric","radii":[30,30,12],"n":20})", kFig12, Convention::Soft,
     1.0, Side::Below},
    {"lp_metric_n4_placed",
     R"({"type":"lp_metric","radii":[0.5,0.9,0.3],"n":4,"translate":[0.1,-0.2,0.1],
         "rotate":{"axis":[0,1,1],"deg":35}})",
     kUnit, Convention::Soft, 1.0, Side::Below},
    {"lp_metric_n0_6", R"({"type":"lp_metric","radii":[1,1,1],"n":0.6})", kUnit, Convention::Soft,
     1.0, Side::Below},
    {"superquadric_bar", R"({"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20})", kFig12,
     Convention::Soft, 1.0, Side::Below},
    // Fig. 14(h)'s cube contour: n1 = n2 = 20, the convex gauges' end-gradient slope.
    {"superquadric_contour_n20", R"({"type":"superquadric","radii":[13,13,24],"n1":20,"n2":20})",
     kFig12, Convention::Soft, 1.0, Side::Below},
    {"superquadric_pinched", R"({"type":"superquadric","radii":[1,1,2],"n1":0.6,"n2":3})", kUnit,
     Convention::Soft, 1.0, Side::Below},
    {"superquadric_round", R"({"type":"superquadric","radii":[1,1.5,1],"n1":2,"n2":1.2})", kUnit,
     Convention::Soft, 1.0, Side::Below},
    {"segment", R"({"type":"segment","p0":[-0.5,0,0],"p1":[0.5,0.3,0.2],"radius":0.7})", kUnit,
     Convention::Soft, 1.0, Side::Below},
    {"segment_point", R"({"type":"segment","p0":[0,0,0],"p1":[0,0,0],"radius":1})", kUnit,
     Convention::Soft, 0.8, Side::Below},
    {"soft_object_blanc",
     R"({"type":"soft_object","distance":{"type":"lp_metric","radii":[1,1,1],"n":2}})", kUnit},
    {"soft_object_blanc_s",
     R"({"type":"soft_object","potential":{"type":"blanc","s":0.7},
         "distance":{"type":"superquadric","radii":[1,0.8,1.2],"n1":1,"n2":4}})",
     kUnit},
    {"soft_object_wyvill",
     R"({"type":"soft_object","potential":{"type":"wyvill"},
         "distance":{"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],"radius":1}})",
     kUnit},
    {"soft_object_murakami",
     R"({"type":"soft_object","potential":{"type":"murakami"},
         "distance":{"type":"lp_metric","radii":[1,1.2,0.9],"n":3}})",
     kUnit},
    {"placed_soft_object",
     R"({"type":"soft_object","translate":[0.2,-0.1,0.3],"rotate":{"axis":[1,1,0],"deg":35},
         "distance":{"type":"lp_metric","radii":[0.6,1,0.4],"n":4}})",
     kUnit},
    {"fig000_12b_soft_blend",
     R"({"type":"soft_blend","children":[
          {"type":"soft_object","distance":{"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20}},
          {"type":"soft_object","distance":{"type":"lp_metric","radii":[30,30,12],"n":20}}]})",
     kFig12},
};

SOFTTRACE_SWEEP_FAMILY(Foundation, kFoundationCases);

}  // namespace
}  // namespace softtrace::test

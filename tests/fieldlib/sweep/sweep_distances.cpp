// Sweep cases for the distance functions of docs/math.md §2 (see sweep.h).
#include <limits>

#include "sweep.h"

namespace softtrace::test {
namespace {

const double kNoRegion = std::numeric_limits<double>::quiet_NaN();
const Box kFig13({-40, -40, -30}, {40, 40, 30});

#define BELOW(level) Convention::Soft, level, Side::Below

const SweepCase kDistanceCases[] = {
    // Planes (§2.3, §2.4): slabs and half-spaces have no finite region.
    {"parallel_planes", R"({"type":"parallel_planes","normal":[1,2,-0.5],"a":0.7})", kUnit,
     BELOW(kNoRegion)},
    {"parallel_planes_placed",
     R"({"type":"parallel_planes","normal":[0,0,3],"a":0.4,"translate":[0.2,0,0.1],
         "rotate":{"axis":[1,0,0],"deg":30}})",
     kUnit, BELOW(kNoRegion)},
    {"one_branch_plane", R"({"type":"one_branch_plane","normal":[0.3,-1,0.4],"a":0.5})", kUnit,
     BELOW(kNoRegion)},
    // Modulated superquadric (002 Eq. 15).
    {"superquadric_t",
     R"({"type":"superquadric","radii":[1,0.8,1.2],"n1":2,"n2":3,"t":[1.5,0.7,2,1,1.2,0.6]})",
     kUnit, BELOW(1.0)},
    {"superquadric_t_pinched",
     R"({"type":"superquadric","radii":[0.8,1,0.9],"n1":0.6,"n2":2.5,"t":[1,1.3,0.8,1,2,1]})",
     kUnit, BELOW(1.0)},
    {"superquadric_t_n_below_1",
     R"({"type":"superquadric","radii":[1,1,1],"n1":1.5,"n2":0.8,"t":[1,2,1,1,1.4,1]})", kUnit,
     BELOW(0.8)},
    {"superquadric_t_placed",
     R"({"type":"superquadric","radii":[0.6,0.5,0.9],"n1":1,"n2":8,"t":[2,1,1,1.5,1,1.1],
         "translate":[0.1,-0.2,0.3],"rotate":{"axis":[1,2,3],"deg":40}})",
     kUnit, BELOW(1.0)},
    // Generalized distance function (000 Eq. 4, 002 Eq. 16).
    {"generalized_axes",
     R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[1,0.7,1.2],"n":2})",
     kUnit, BELOW(1.0)},
    {"generalized_octa_t",
     R"({"type":"generalized_distance","normals":[[1,1,1],[1,-1,1],[-1,1,1],[1,1,-1]],
         "a":0.8,"n":4,"t_pos":[1,1.5,2,1],"t_neg":[1.2,1,1,0.7]})",
     kUnit, BELOW(1.0)},
    {"generalized_n1",
     R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1],[1,1,0],[0,1,1]],
         "a":[1,1,1,1.2,1.2],"n":1})",
     kUnit, BELOW(1.5)},
    {"generalized_n20",
     R"({"type":"generalized_distance","normals":[[1,0.2,0],[0,1,0.3],[0.1,0,1]],"a":[1,0.8,0.6],
         "n":20,"t_pos":[1,1,2],"t_neg":[1.1,1,1]})",
     kUnit, BELOW(1.0)},
    {"generalized_n_below_1",
     R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1],[1,1,1]],"a":1,
         "n":0.7})",
     kUnit, BELOW(1.0)},
    {"generalized_two_normals",
     R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,1]],"a":[0.5,0.8],"n":3})", kUnit,
     BELOW(kNoRegion)},
    {"generalized_placed",
     R"({"type":"generalized_distance","normals":[[1,0,0],[0,1,0],[0,0,1]],"a":[0.5,0.7,0.6],
         "n":6,"t_pos":[2,1,1],"t_neg":[1,1,1.5],"translate":[0.3,0,-0.2],
         "rotate":{"axis":[0,1,1],"deg":25}})",
     kUnit, BELOW(1.0)},
    // Super-elliptic cylinder (002 Eqs. 17, 18).
    {"cylinder", R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":3,
                     "half_length":0.6})",
     kUnit, BELOW(1.0)},
    {"cylinder_t", R"({"type":"superelliptic_cylinder","radii":[0.5,0.7,0.4],"n":2,
                       "half_length":0.5,"t":[1.2,2,1,1.5,1.3,0.7]})",
     kUnit, BELOW(1.0)},
    {"cylinder_n_below_1", R"({"type":"superelliptic_cylinder","radii":[0.6,0.6,0.5],"n":0.8,
                               "half_length":0.3,"t":[1,1,1,1,2,1]})",
     kUnit, BELOW(1.0)},
    {"cylinder_no_spine", R"({"type":"superelliptic_cylinder","radii":[0.6,0.5,0.7],"n":1,
                              "half_length":0})",
     kUnit, BELOW(1.0)},
    {"cylinder_placed", R"({"type":"superelliptic_cylinder","radii":[0.4,0.4,0.3],"n":20,
                            "half_length":0.7,"translate":[0,0.2,0],
                            "rotate":{"axis":[1,0,0],"deg":90}})",
     kUnit, BELOW(1.0)},
    // Torus (circle skeleton).
    {"torus", R"({"type":"torus","major_radius":0.8,"radii":[0.3,0.4]})", kUnit, BELOW(1.0)},
    {"torus_n1_5", R"({"type":"torus","major_radius":1,"radii":[0.5,0.3],"n":1.5})", kUnit,
     BELOW(1.0)},
    {"torus_n_below_1", R"({"type":"torus","major_radius":0.7,"radii":[0.4,0.4],"n":0.7})", kUnit,
     BELOW(1.0)},
    {"torus_placed", R"({"type":"torus","major_radius":0.6,"radii":[0.3,0.2],"n":8,
                         "translate":[0.1,0.1,0],"rotate":{"axis":[0,1,0],"deg":60}})",
     kUnit, BELOW(1.0)},
    // Polar prisms: docs/math.md §10.1's rose bar and star contour, and a small one.
    {"polar_prism_rose", R"({"type":"polar_prism","radius":8,"lobes":5,"amplitude":0.3,
                             "profile":"cosine","half_height":24})",
     kFig13, BELOW(1.0)},
    {"polar_prism_star", R"({"type":"polar_prism","radius":13,"lobes":5,"amplitude":0.35,
                             "profile":"triangle","half_height":24})",
     kFig13, BELOW(1.0)},
    {"polar_prism_small", R"({"type":"polar_prism","radius":0.8,"lobes":3,"amplitude":0.6,
                              "profile":"triangle","half_height":0.7,"n":3})",
     kUnit, BELOW(1.0)},
    {"polar_prism_placed", R"({"type":"polar_prism","radius":0.7,"lobes":2,"amplitude":0.5,
                               "profile":"cosine","half_height":0.9,"n":2,
                               "translate":[0,0.3,0],"rotate":{"axis":[1,1,0],"deg":50}})",
     kUnit, BELOW(1.0)},
    // Super-ellipsoidal blends of ray-linear functions (modulation/contour surfaces).
    {"se_union",
     R"({"type":"super_ellipsoidal_union","n":4,"children":[
          {"type":"lp_metric","radii":[1,0.5,0.5],"n":2},
          {"type":"superquadric","radii":[0.4,0.8,0.6],"n1":1.5,"n2":3,"t":[1,1,2,1,1,1]}]})",
     kUnit, BELOW(1.0)},
    {"se_union_placed_children",
     R"({"type":"super_ellipsoidal_union","n":2,"children":[
          {"type":"lp_metric","radii":[0.5,0.5,0.5],"n":2,"translate":[0.5,0,0]},
          {"type":"lp_metric","radii":[0.5,0.4,0.5],"n":3,"translate":[-0.5,0,0]},
          {"type":"torus","major_radius":0.5,"radii":[0.2,0.2]}]})",
     kUnit, BELOW(0.8)},
    {"se_intersection_planes",
     R"({"type":"super_ellipsoidal_intersection","n":8,"children":[
          {"type":"parallel_planes","normal":[1,0,0],"a":1},
          {"type":"parallel_planes","normal":[0,1,0],"a":0.8},
          {"type":"parallel_planes","normal":[0,0,1],"a":0.6}]})",
     kUnit, BELOW(kNoRegion)},
    {"se_intersection_one_branch",
     R"({"type":"super_ellipsoidal_intersection","n":3,"children":[
          {"type":"one_branch_plane","normal":[1,0,0],"a":1},
          {"type":"one_branch_plane","normal":[-1,0,0],"a":0.5},
          {"type":"one_branch_plane","normal":[0,1,0],"a":0.7},
          {"type":"lp_metric","radii":[1,1,0.6],"n":2}]})",
     kUnit, BELOW(1.0)},
    {"se_intersection_n_below_1",
     R"({"type":"super_ellipsoidal_intersection","n":0.8,"children":[
          {"type":"lp_metric","radii":[1,0.6,0.8],"n":2},
          {"type":"polar_prism","radius":0.8,"lobes":4,"amplitude":0.2,"profile":"cosine",
           "half_height":1}]})",
     kUnit, BELOW(1.0)},
    {"se_intersection_of_unions",
     R"({"type":"super_ellipsoidal_intersection","n":2,"rotate":{"axis":[0,0,1],"deg":20},
         "children":[
          {"type":"super_ellipsoidal_union","n":6,"children":[
            {"type":"lp_metric","radii":[1,0.4,0.4],"n":2},
            {"type":"lp_metric","radii":[0.4,1,0.4],"n":2}]},
          {"type":"superelliptic_cylinder","radii":[0.9,0.9,0.3],"n":4,"half_length":0.3}]})",
     kWide, BELOW(1.0)},
};

#undef BELOW

SOFTTRACE_SWEEP_FAMILY(Distances, kDistanceCases);

#undef BELOW

}  // namespace
}  // namespace softtrace::test

// Sweep cases for offset and the BT_k blends (zero convention; see sweep.h). Children are offset
// distance functions d - 1 (inside <= 0), placed so the blending bands cross the domain.
#include "sweep.h"

namespace softtrace::test {
namespace {

constexpr Convention kZero = Convention::Zero;

#define BALL(x, r)                                                                               \
  R"({"type":"offset","translate":[)" #x R"(,0,0],"children":[{"type":"lp_metric","radii":[)" #r \
  "," #r "," #r R"(],"n":2}]})"
#define BAR \
  R"({"type":"offset","scale":0.7,"children":[{"type":"superquadric","radii":[0.4,0.5,1.2],"n1":2,"n2":6}]})"
#define ROD \
  R"({"type":"offset","level":1,"children":[{"type":"segment","p0":[0,-1,-0.3],"p1":[0,1,0.4],"radius":0.3}]})"

const SweepCase kBtCases[] = {
    {"offset_lp",
     R"({"type":"offset","children":[{"type":"lp_metric","radii":[1,0.8,1.2],"n":3}]})", kUnit,
     kZero, 0.0, Side::Below},
    {"offset_scaled_level", BAR, kUnit, kZero, 0.0, Side::Below},
    {"offset_negative_scale",
     R"({"type":"offset","scale":-2,"level":0.5,"children":[{"type":"segment","p0":[0,0,-0.5],"p1":[0,0,0.5],"radius":0.6}]})",
     kUnit, kZero, 0.0, Side::Above},
    {"bt_union_conic",
     R"({"type":"bt_union","base":"conic","r1":0.3,"r2":0.5,"p":0,"m":[1,2],"children":[)" BALL(
         -0.4, 0.6) "," BALL(0.45, 0.5) "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_union_conic_hyperbola",
     R"({"type":"bt_union","base":"conic","r1":0.4,"r2":0.3,"p":-0.4,"m":[0.5,1.5],"children":[)" BAR
     "," ROD "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_union_conic_ellipse",
     R"({"type":"bt_union","base":"conic","r1":0.4,"r2":0.4,"p":0.1,"children":[)" BALL(
         -0.3, 0.5) "," ROD "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_union_hyper3",
     R"({"type":"bt_union","base":"hyperellipsoid","r":[0.3,0.4,0.2],"p":[2,3,1.5],"m":[1,0.5,2],
         "children":[)" BALL(-0.5, 0.5) "," BAR "," ROD "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_intersection_conic",
     R"({"type":"bt_intersection","base":"conic","r1":0.3,"r2":0.2,"p":-0.05,"m":[1,0.6],"children":[)" BALL(
         -0.3, 0.8) "," BALL(0.3, 0.7) "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_intersection_hyper3",
     R"({"type":"bt_intersection","base":"hyperellipsoid","r":0.25,"p":[2,4,1.3],"m":[1,1.5,0.7],
         "children":[)" BALL(-0.2, 0.9) "," BAR "," BALL(0.3, 0.8) "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_difference_conic",
     R"({"type":"bt_difference","base":"conic","r1":0.2,"r2":0.3,"p":0,"m":[1,0.5],"children":[)" BALL(
         0, 1) "," ROD "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_difference_hyper3",
     R"({"type":"bt_difference","base":"hyperellipsoid","r":[0.2,0.3,0.25],"p":2.5,"children":[)" BALL(
         0, 1) "," ROD "," BALL(0.9, 0.4) "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"displacement_union_hyper",
     R"({"type":"displacement_union","base":"hyperellipsoid","r":[0.3,0.3],"p":[2,2],"children":[)" BALL(
         -0.4, 0.5) "," BAR "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"displacement_union_conic",
     R"({"type":"displacement_union","base":"conic","r1":0.3,"r2":0.3,"p":-0.2,"children":[)" BALL(
         -0.4, 0.5) "," ROD "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_nested_sequential",  // 003 Fig. 9's structure BT2(BT2(f1, f2), f3) without bulges
     R"({"type":"bt_union","base":"conic","r1":0.3,"r2":0.3,"p":0,"children":[
          {"type":"bt_union","base":"hyperellipsoid","r":[0.2,0.2],"p":[2,2],"m":[0.3,1],
           "children":[)" BAR "," ROD "]}," BALL(0.7, 0.4) "]}",
     kUnit, kZero, 0.0, Side::Below},
    {"bt_placed",
     R"({"type":"bt_intersection","base":"conic","r1":0.2,"r2":0.3,"p":0,"m":[2,1],
         "translate":[0.1,0.2,-0.1],"rotate":{"axis":[1,0,1],"deg":40},"children":[)" BAR
     "," BALL(0.2, 0.8) "]}",
     kUnit, kZero, 0.0, Side::Below},
};

#undef BALL
#undef BAR
#undef ROD

SOFTTRACE_SWEEP_FAMILY(BT, kBtCases);

#undef BALL
#undef BAR
#undef ROD

}  // namespace
}  // namespace softtrace::test

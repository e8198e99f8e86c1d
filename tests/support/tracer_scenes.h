// The tracer tests' scenes (one object each) and their reference: a dense march for the first
// point inside the solid.
#pragma once

#include <iterator>
#include <limits>

#include "trace/tracer.h"

namespace softtrace::tracer_scenes {

// Fields with and without global bounds, in both conventions; the last is a sum of polynomial
// blobs (kBlobs).
inline const char* const kScenes[] = {
    // Fig. 12(b).
    R"({"camera":{"eye":[62,-82,56],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","distance":{"type":"superquadric","radii":[8,8,24],"n1":1,"n2":20}},
        {"type":"soft_object","distance":{"type":"lp_metric","radii":[30,30,12],"n":20}}]}}]})",
    // A pinched superquadric (n1 = 0.6: not Lipschitz) next to a segment.
    R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","distance":{"type":"superquadric","radii":[10,10,14],"n1":0.6,"n2":3}},
        {"type":"soft_object","distance":{"type":"segment","p0":[-12,0,6],"p1":[12,4,6],"radius":5}}]}}]})",
    // Constructive convention on a plain distance function (inside d <= 1).
    R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"convention":"constructive",
        "field":{"type":"lp_metric","radii":[6,9,4],"n":1.5}}]})",
    // Polynomial blobs (the local mode traces them as polynomials, tracer_blobs.cpp): overlapping
    // ellipsoids, some rotated, Murakami's and Wyvill's potentials, and a thin one.
    R"({"camera":{"eye":[30,-40,20],"target":[0,0,0]},"objects":[{"field":{"type":"soft_blend","children":[
        {"type":"soft_object","potential":{"type":"murakami"},"distance":{"type":"lp_metric","radii":[5,5,5],"n":2}},
        {"type":"soft_object","potential":{"type":"wyvill"},"translate":[4,1,0],
         "distance":{"type":"lp_metric","radii":[3,6,2],"n":2,"rotate":{"axis":[1,1,0],"deg":40}}},
        {"type":"soft_object","potential":{"type":"murakami"},"translate":[-3,-4,2],
         "distance":{"type":"lp_metric","radii":[4,2,3],"n":2}},
        {"type":"soft_object","potential":{"type":"wyvill"},"translate":[0,5,-3],
         "distance":{"type":"lp_metric","radii":[9,0.6,0.6],"n":2,"rotate":{"axis":[0,0,1],"deg":25}}},
        {"type":"soft_object","potential":{"type":"murakami"},"translate":[8,-6,4],
         "distance":{"type":"lp_metric","radii":[1.5,1.5,1.5],"n":2}}]}}]})",
};
constexpr int kCount = int(std::size(kScenes));
constexpr int kBlobs = kCount - 1;

// The first t of n + 1 evenly spaced samples of [t0, t1] inside the solid, or inf.
inline double reference_first_hit(const ObjectTracer& tr, const Ray& ray, double t0, double t1,
                                  int n) {
  for (int i = 0; i <= n; ++i) {
    const double t = t0 + (t1 - t0) * i / n;
    if (tr.inside(ray.o + ray.d * t)) return t;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace softtrace::tracer_scenes

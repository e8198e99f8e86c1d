// The papers' preconditions for surface-defined radii (002 §4.1, §4.2; 000 §IV.B), checked at load:
// (b) the modulation (or contour) has the distance's skeleton structure, and (c) it lies on the
// right side of the distance: f_a <= d for T_an/T_al, fc <= 2d for contour, f_s >= d for
// T_sn/T_sr. docs/scene-format.md says exactly what is checked.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "describe/build_context.h"
#include "model/node.h"

namespace softtrace {

// "point", "segment", "circle", "plane", or "" when unknown (combinations), for the distance
// node `j` as written in the scene (degenerate parameters included: a zero-length segment is a
// point).
std::string skeleton_of(const nlohmann::json& j);

// (b): fails at r/key when the modulation's skeleton is known and differs from ctx.skeleton.
void check_same_skeleton(const Params& r, const std::string& key, const BuildContext& ctx);

// (c), sampled: `field` is the transformed soft object built from `d` and `f` (f scaled by
// `scale`, so that the condition reads scale*f <= d when `outer`, scale*f >= d otherwise).
// 1024 fixed-seed points in the field's support box (a quarter each in boxes 8 and 64 times smaller
// about its centre); a failure at a point with d >= 0.25 is a
// located error at r/key naming the point, failures only nearer the skeleton a warning.
void check_modulation_side(const Params& r, const std::string& key, const FieldNode& field,
                           const FieldNode& d, const FieldNode& f, double scale, bool outer,
                           const BuildContext& ctx);

}  // namespace softtrace

#include "loader/placement_keys.h"

#include <cmath>
#include <string>

#include "math/affine.h"
#include "model/placement.h"

namespace softtrace {

namespace {

// Beyond this condition number |A| |A^-1| a matrix is numerically singular: its inverse's entries
// carry fewer than 4 significant digits.
constexpr double kMaxCondition = 1e12;

// Rotations are periodic: reduce the angle before it meets π, so that no finite angle overflows.
Mat3 rotation_of(const Params& r) {
  r.check_keys({"axis", "deg"});  // a misspelled key before a missing one, as everywhere
  const Vec3 axis = r.vec3("axis");
  r.check(length(axis) > 0 && std::isfinite(length(axis)), "axis", "expected a non-zero axis");
  return Mat3::rotation(axis, std::fmod(r.number("deg"), 360.0));
}

// `key`'s element `i` (its pointer is built only for an error: every component reads these).
void check_magnitude(const Params& p, const char* key, int i, double v) {
  if (!(std::abs(v) <= kMaxMagnitude))
    p.fail(key + ("/" + std::to_string(i)),
           "expected a number of magnitude at most 1e150 (docs/scene-format.md)");
}

// `matrix`: three rows [a, b, c, t], the object-to-world map x -> A x + t.
void read_matrix(const Params& p, Mat3* A, Vec3* t) {
  const auto& m = p.get("matrix");
  p.check(m.is_array() && m.size() == 3, "matrix",
          "expected 3 rows [a, b, c, t] (the object-to-world map, docs/scene-format.md)");
  for (int i = 0; i < 3; ++i) {
    const auto& row = m.at(i);
    p.check_at(row.is_array() && row.size() == 4, "matrix", i, "expected a row of 4 numbers");
    for (int j = 0; j < 4; ++j) {
      const std::string at = std::to_string(i) + "/" + std::to_string(j);
      if (!row.at(j).is_number()) p.fail_at("matrix", at, "expected a number");
      const double v = row.at(j).get<double>();
      if (!(std::abs(v) <= kMaxMagnitude))
        p.fail_at("matrix", at, "expected a number of magnitude at most 1e150");
      if (j < 3)
        A->r[i][j] = v;
      else
        (*t)[i] = v;
    }
  }
}

}  // namespace

bool placed_by_translation_only(const nlohmann::json& j, const KindInfo& kind) {
  for (const auto& [key, value] : j.get_ref<const nlohmann::json::object_t&>())
    if (same_name(key, "matrix") || same_name(key, "rotate") ||
        (same_name(key, "scale") && !find_param(kind, "scale")))
      return false;
  return true;
}

bool place_translated(NodePtr& node, const nlohmann::json* translate) {
  if (!translate) return true;
  const nlohmann::json& v = *translate;
  if (!v.is_array() || v.size() != 3) return false;
  Vec3 t;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) return false;
    t[i] = v[i].get<double>();
    if (!(std::abs(t[i]) <= kMaxMagnitude)) return false;
  }
  if (t.x != 0 || t.y != 0 || t.z != 0) node = place(std::move(node), Mat3(), t);
  return true;
}

NodePtr apply_placement(NodePtr node, const Params& p, const KindInfo& kind) {
  const bool own_scale = find_param(kind, "scale") != nullptr;
  const bool has_matrix = p.has("matrix"), has_scale = !own_scale && p.has("scale");
  if (has_matrix)
    for (const char* other : {"translate", "rotate", "scale"})
      if (p.has(other) && !(own_scale && std::string(other) == "scale"))
        p.fail("matrix", std::string("'matrix' cannot be combined with '") + other +
                             "' (fold it into the matrix; docs/scene-format.md \"Placement\")");
  Vec3 translate;
  if (p.has("translate")) {
    translate = p.vec3("translate");
    for (int i = 0; i < 3; ++i) check_magnitude(p, "translate", i, translate[i]);
  }
  Mat3 A;  // object to world: R diag(scale), or the matrix
  bool rotated = false, affine = false;
  if (p.has("rotate")) {
    const Params r = p.object("rotate");
    A = rotation_of(r);
    r.finish();
    rotated = true;
  }
  if (has_scale) {
    const Vec3 s = p.vec3("scale");
    for (int i = 0; i < 3; ++i) {
      check_magnitude(p, "scale", i, s[i]);
      if (s[i] == 0) p.fail_at("scale", std::to_string(i), "expected a non-zero scale factor");
      if (!(std::abs(s[i]) >= kMinPositive))
        p.fail_at("scale", std::to_string(i),
                  "expected a scale factor of magnitude at least 1e-150");
    }
    affine = s.x != 1 || s.y != 1 || s.z != 1;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A.r[i][j] *= s[j];  // R diag(s): scale first, then rotate
  }
  const char* linear_key = has_scale ? "scale" : "rotate";
  if (has_matrix) {
    read_matrix(p, &A, &translate);
    affine = true;
    linear_key = "matrix";
  }
  if (affine) {
    const double det = determinant(A);
    const double cond = operator_norm_bound(A) * operator_norm_bound(inverse(A));
    p.check(det != 0 && std::isfinite(det) && cond <= kMaxCondition, linear_key,
            "expected an invertible linear part with condition number at most 1e12 (got " +
                (det == 0 || !std::isfinite(cond) ? std::string("a singular one")
                                                  : std::to_string(cond)) +
                "; docs/scene-format.md \"Placement\")");
    return place_affine(std::move(node), A, translate);
  }
  if (rotated || translate.x != 0 || translate.y != 0 || translate.z != 0)
    return place(std::move(node), A, translate);
  return node;
}

}  // namespace softtrace

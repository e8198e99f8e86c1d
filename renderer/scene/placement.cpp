#include "scene/placement.h"

#include <cmath>

#include "math/affine.h"
#include "scene/ranges.h"

namespace softtrace {

bool has_placement(const Params& p) {
  return p.has("scale") || p.has("rotate") || p.has("translate") || p.has("matrix");
}

Affine load_placement(const Params& p) {
  Affine m;
  if (p.has("scale")) {
    const Vec3 s = p.vec3("scale");
    for (int i = 0; i < 3; ++i)
      p.check(std::abs(s[i]) >= 1e-12 && std::abs(s[i]) <= 1e12, "scale/" + std::to_string(i),
              "expected a scale factor of magnitude between 1e-12 and 1e12");
    m.linear = Mat3{{{s.x, 0, 0}, {0, s.y, 0}, {0, 0, s.z}}};
  }
  if (p.has("rotate")) {
    const Params r = p.object("rotate");
    r.check_keys({"axis", "deg"});
    const Vec3 axis = r.vec3("axis");
    r.check(max_abs(axis) > 0, "axis", "expected a non-zero axis");
    const double deg = r.number("deg");
    r.finish();
    m.linear = times(Mat3::rotation(unit(axis), deg), m.linear);
  }
  if (p.has("translate")) {
    m.offset = p.vec3("translate");
    p.check(max_abs(m.offset) <= kMaxPosition, "translate",
            std::string("expected a translation ") + kPositionRule);
  }
  if (p.has("matrix")) {
    const nlohmann::json& rows = p.get("matrix");
    const auto ok = [&] {
      if (!rows.is_array() || rows.size() != 3) return false;
      for (const auto& row : rows) {
        if (!row.is_array() || row.size() != 4) return false;
        for (const auto& v : row)
          if (!v.is_number() || !(std::abs(v.get<double>()) <= 1e12)) return false;
      }
      return true;
    };
    if (!ok()) p.fail("matrix", "expected 3 rows [a, b, c, t] of numbers within 1e12");
    Affine l;
    for (int i = 0; i < 3; ++i) {
      l.linear.r[i] = {rows[i][0].get<double>(), rows[i][1].get<double>(),
                       rows[i][2].get<double>()};
      l.offset[i] = rows[i][3].get<double>();
    }
    m = compose(l, m);
  }
  return m;
}

bool invert(const Mat3& m, Mat3& inv) {
  const double det = determinant(m);
  inv = inverse(m);
  return std::isfinite(det) && std::abs(det) > 1e-30 && max_abs(inv.r[0]) < 1e30 &&
         max_abs(inv.r[1]) < 1e30 && max_abs(inv.r[2]) < 1e30;
}

}  // namespace softtrace

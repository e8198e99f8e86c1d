#include "model/modulation_check.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "describe/building.h"

namespace softtrace {

namespace {

bool same_point(const nlohmann::json& a, const nlohmann::json& b) {
  return a.is_array() && b.is_array() && a == b;
}

// A small deterministic generator (splitmix64): the same points on every platform.
struct Points {
  uint64_t state = 0x2545F4914F6CDD1DULL;
  double next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  Vec3 in(const Box& b) {
    const double x = next(), y = next(), z = next();
    return {b.lo.x + x * (b.hi.x - b.lo.x), b.lo.y + y * (b.hi.y - b.lo.y),
            b.lo.z + z * (b.hi.z - b.lo.z)};
  }
};

std::string point_text(const Vec3& p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

}  // namespace

std::string skeleton_of(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("type") || !j.at("type").is_string()) return "";
  const KindInfo* kind = find_kind(j.at("type").get<std::string>(), KindGroup::Node);
  if (!kind) return "";
  const std::string s = kind->skeleton;
  const auto zero = [&](const char* key) {
    return j.contains(key) && j.at(key).is_number() && j.at(key).get<double>() == 0;
  };
  if (s == "segment" && j.contains("p0") && same_point(j.at("p0"), j.value("p1", nlohmann::json())))
    return "point";
  if (s == "segment" && zero("half_length")) return "point";
  if (s == "circle" && zero("major_radius")) return "point";
  return s;
}

void check_same_skeleton(const Params& r, const std::string& key, const BuildContext& ctx) {
  const std::string mine = skeleton_of(r.raw().at(key));
  if (mine.empty() || ctx.skeleton.empty() || mine == ctx.skeleton) return;
  r.fail(key, "expected the distance's skeleton structure (002 §4.1 (b)): the distance has a " +
                  ctx.skeleton + " skeleton, this " +
                  r.raw().at(key).at("type").get<std::string>() + " a " + mine);
}

void check_modulation_side(const Params& r, const std::string& key, const FieldNode& field,
                           const FieldNode& d, const FieldNode& f, double scale, bool outer,
                           const BuildContext& ctx) {
  const Box box = field.region(std::numeric_limits<double>::min(), Side::Above);
  if (!box.bounded()) return;
  const char* condition = outer ? (scale == 1 ? "f_a <= d" : "fc <= 2d") : "f_s >= d";
  Points rng;
  bool near_skeleton = false;
  Vec3 near_point;
  // Half the points in the box, a quarter each in boxes 8 and 64 times smaller about its centre,
  // where the skeleton usually is.
  const Vec3 c = box.center(), e = box.extent() * 0.5;
  const Box inner(c - e / 8, c + e / 8), core(c - e / 64, c + e / 64);
  for (int i = 0; i < 1024; ++i) {
    const Vec3 X = rng.in(i < 512 ? box : i < 768 ? inner : core);
    const double dv = d.value(X), fv = scale * f.value(X);
    const double slack = 1e-9 * (std::abs(dv) + std::abs(fv)) + 1e-12;
    const bool bad = outer ? fv > dv + slack : fv < dv - slack;
    if (!bad) continue;
    if (dv >= 0.25) {
      std::ostringstream m;
      m.precision(6);
      m << "expected " << condition
        << (scale == 1 ? " (002 §4.1-4.2 (c)), but at "
                       : " (000 §IV.B: fc = 1 encloses d = 0.5), but at ")
        << point_text(X) << " d = " << dv << " and "
        << (outer ? (scale == 1 ? "f_a" : "fc/2") : "f_s") << " = " << fv;
      r.fail(key, m.str());
    }
    if (!near_skeleton) near_point = X;
    near_skeleton = true;
  }
  if (near_skeleton)
    warn(ctx, r.where(key) + ": " + condition + " fails near the skeleton, e.g. at " +
                  point_text(near_point) + " (d < 0.25 there: only the inner profile changes)");
}

}  // namespace softtrace

#include "loader/build.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "describe/building.h"
#include "describe/params.h"

namespace softtrace {

namespace {
nlohmann::json vec(const Vec3& v) {
  return {v.x, v.y, v.z};
}
nlohmann::json list(const std::vector<Spec>& specs) {
  nlohmann::json a = nlohmann::json::array();
  for (const Spec& s : specs) a.push_back(s.json());
  return a;
}
}  // namespace

Spec& Spec::set(const std::string& key, nlohmann::json value) {
  json_[key] = std::move(value);
  return *this;
}

Spec kind(const std::string& type, nlohmann::json params) {
  if (!params.is_object()) throw std::invalid_argument("kind(): parameters must be an object");
  params["type"] = type;
  return Spec(std::move(params));
}

Spec lp_metric(const Vec3& radii, double n) {
  return kind("lp_metric", {{"radii", vec(radii)}, {"n", n}});
}
Spec blanc(double s) {
  return kind("blanc", {{"s", s}});
}
Spec wyvill() {
  return kind("wyvill");
}
Spec murakami() {
  return kind("murakami");
}

Spec soft_object(const Spec& distance, const Spec& potential) {
  return kind("soft_object", {{"distance", distance.json()}, {"potential", potential.json()}});
}
Spec soft_blend(const std::vector<Spec>& children) {
  return kind("soft_blend", {{"children", list(children)}});
}

Spec translate(Spec node, const Vec3& offset) {
  Vec3 total = offset;
  const nlohmann::json& j = node.json();
  const auto it = j.find("translate");
  if (it != j.end() && it->is_array() && it->size() == 3 &&
      std::all_of(it->begin(), it->end(), [](const nlohmann::json& v) { return v.is_number(); }))
    for (int i = 0; i < 3; ++i) total[i] += (*it)[i].get<double>();
  return std::move(node.set("translate", vec(total)));
}

Spec rotate(Spec node, const Vec3& axis, double degrees) {
  if (node.json().contains("translate") || node.json().contains("rotate"))
    throw std::invalid_argument(
        "rotate(): the node is already placed; rotate it before translating it");
  return std::move(node.set("rotate", {{"axis", vec(axis)}, {"deg", degrees}}));
}

NodePtr build(const Spec& spec, Convention convention, const std::string& name) {
  BuildContext ctx;
  ctx.slot = Family::ConventionField;
  ctx.convention = convention;
  const Params p(spec.json(), "", std::make_shared<const std::string>(name));
  if (!spec.json().is_object() || !spec.json().contains("type"))
    p.fail("", "expected a node object with a \"type\"");
  return build_field(p, ctx);
}

}  // namespace softtrace

// Fields from code, without writing JSON: builders named as the scene format's kinds
// (docs/scene-format.md) that assemble the same description a scene file holds, and `build`,
// which hands it to the loader (registry.h). Validation is the loader's, so a bad parameter
// throws SceneError with the same message a scene file gets, located by JSON pointer:
//   softtrace: <built field>: /children/1/distance/radii/2: expected a number > 0
//
//   using namespace softtrace;
//   const NodePtr f = build(soft_blend({
//       soft_object(lp_metric({30, 30, 12}, 20), wyvill()),
//       translate(soft_object(lp_metric({10, 10, 10}, 2), murakami()), {25, 0, 0})}));
//   const Program p = compile(*f);  // program.h; evaluate with eval.h or batch.h
//
// Kinds without a builder of their own (every kind in `softtrace nodes`) are reached with
// `kind("perlin_union", {{"children", ...}})`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "math/convention.h"
#include "math/vec.h"
#include "model/node.h"

namespace softtrace {

// The description of a node, potential or radius transform: its scene-format JSON object.
class Spec {
 public:
  explicit Spec(nlohmann::json j) : json_(std::move(j)) {}
  const nlohmann::json& json() const { return json_; }
  // Sets parameter `key` (any kind's, as docs/scene-format.md names them); returns *this.
  Spec& set(const std::string& key, nlohmann::json value);

 private:
  nlohmann::json json_;
};

// Any kind by name, with its parameters (node-valued ones as Spec::json() values).
Spec kind(const std::string& type, nlohmann::json params = nlohmann::json::object());

// Distances.
Spec lp_metric(const Vec3& radii, double n);
// Potentials.
Spec blanc(double s = 0);
Spec wyvill();
Spec murakami();
// Soft objects and blends.
Spec soft_object(const Spec& distance, const Spec& potential);
Spec soft_blend(const std::vector<Spec>& children);
// Placement, as a scene's "rotate" and "translate" keys: the node turned by `degrees` about `axis`
// through the origin, then moved by `offset`. Translations add up; rotating a node that is
// already translated throws std::invalid_argument (write rotate(...) innermost).
Spec translate(Spec node, const Vec3& offset);
Spec rotate(Spec node, const Vec3& axis, double degrees);

// Builds the node described by `spec` for an object of convention `convention` (the family its
// field must have; Convention::Soft checks for a soft field). `name` places error messages.
// Throws SceneError.
NodePtr build(const Spec& spec, Convention convention = Convention::Soft,
              const std::string& name = "<built field>");

}  // namespace softtrace

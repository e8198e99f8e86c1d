// Per-component materials (docs/scene-format.md "Component materials", docs/math.md "Blended
// materials"): the soft fields reached from an object's field through soft_blend nodes (at any
// depth) are its components; each may carry a "material", and a shaded point mixes the
// components' materials with weights |s_i f_i(p)| / Σ_j |s_j f_j(p)|, POV-Ray 3.7's blob texture
// rule. fieldlib never sees the "material" keys: they are read and taken out here.
#pragma once

#include <memory>
#include <vector>

#include "describe/building.h"
#include "math/box.h"
#include "model/node.h"
#include "scene/material.h"

namespace softtrace {

class ComponentMaterials {
 public:
  struct Component {
    NodePtr field;  // s_i f_i in world coordinates (the soft_blends above it keep their placement)
    Box support;    // where it is non-zero
    int material;   // index into materials(); 0 is the object's own
  };
  struct Weight {
    int material;
    double weight;
  };

  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<Component>& components() const { return components_; }

  // The weights at `p` into `out` (cleared first), one per material with a non-zero component
  // there, summing to 1, in the order of the materials; empty where every component is 0.
  void weights(const Vec3& p, std::vector<Weight>& out) const;

 private:
  friend NodePtr build_object_field(const Params& field, const BuildContext& ctx,
                                    const Material& object_material,
                                    std::shared_ptr<const ComponentMaterials>* components);
  std::vector<Material> materials_;
  std::vector<Component> components_;
};

// Builds an object's field from `field`. When a component under soft_blends has a "material",
// that key is read (its errors located as usual), the field is built from a copy without it, and
// *components receives the components; otherwise the field is built as it stands and
// *components is null.
NodePtr build_object_field(const Params& field, const BuildContext& ctx,
                           const Material& object_material,
                           std::shared_ptr<const ComponentMaterials>* components);

}  // namespace softtrace

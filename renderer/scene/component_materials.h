// Per-component materials (docs/scene-format.md "Component materials", docs/math.md "Blended
// materials"): the soft fields reached from an object's field through soft_blend nodes (at any
// depth) are its components; each may carry a "material", and a shaded point mixes the
// components' materials with weights |s_i f_i(p)| / Σ_j |s_j f_j(p)|, POV-Ray 3.7's blob texture
// rule. fieldlib never sees the "material" keys: they are read and taken out here.
#pragma once

#include <memory>
#include <vector>

#include "describe/building.h"
#include "model/node.h"
#include "program/program.h"
#include "scene/material.h"

namespace softtrace {

class ComponentMaterials {
 public:
  struct Weight {
    int material;
    double weight;
  };

  const std::vector<Material>& materials() const { return materials_; }
  // The object's field compiled with its components as the program's terms (Program::terms),
  // component i term i: the tracer's program (trace_target), whose one gradient walk at a hit
  // gives the normal and the components' values (gradient_terms).
  const std::shared_ptr<const Program>& program() const { return program_; }
  int size() const { return static_cast<int>(material_of_.size()); }

  // The weights from the components' values s_i f_i(p) (terms[0, size())) into `out` (cleared
  // first), one per material with a non-zero component there, summing to 1, in the order of the
  // materials; empty where every component is 0.
  void weights(const double* terms, std::vector<Weight>& out) const;
  // The same at `p`, from a walk of program() of its own (where no normal is computed with it:
  // a CSG operand's face, a mesh's vertices).
  void weights(const Vec3& p, std::vector<Weight>& out) const;

 private:
  friend NodePtr build_object_field(const Params& field, const BuildContext& ctx,
                                    const Material& object_material,
                                    std::shared_ptr<const ComponentMaterials>* components);
  std::vector<Material> materials_;
  std::vector<int> material_of_;  // component i's index into materials(); 0 is the object's own
  std::shared_ptr<const Program> program_;
};

// Builds an object's field from `field`. When a component under soft_blends has a "material",
// that key is read (its errors located as usual), the field is built from a copy without it, and
// *components receives the components (the soft fields directly under soft_blends, found by
// their JSON objects as fieldlib builds them) and the program; otherwise the field is built as
// it stands and *components is null.
NodePtr build_object_field(const Params& field, const BuildContext& ctx,
                           const Material& object_material,
                           std::shared_ptr<const ComponentMaterials>* components);

}  // namespace softtrace

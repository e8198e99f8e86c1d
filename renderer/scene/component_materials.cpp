#include "scene/component_materials.h"

#include <cmath>
#include <string>

namespace softtrace {

namespace {

using json = nlohmann::json;

// A component found under the soft_blends: where it is (child indices from the field's root) and
// the soft_blends above it, outermost first.
struct Found {
  std::vector<size_t> path;
  std::vector<const json*> blends;
  const json* node;
  int material;
};

std::string type_of(const json& node) {
  return node.is_object() && node.contains("type") && node.at("type").is_string()
             ? node.at("type").get<std::string>()
             : "";
}

// Walks the soft_blends from `p`, reading each soft_object child's "material" into `materials`.
void collect(const Params& p, std::vector<size_t>& path, std::vector<const json*>& blends,
             std::vector<Material>& materials, std::vector<Found>& found) {
  const json& raw = p.raw();
  if (type_of(raw) != "soft_blend") {
    int material = 0;
    if (type_of(raw) == "soft_object" && p.has("material")) {
      materials.push_back(load_material(p.object("material")));
      material = static_cast<int>(materials.size()) - 1;
    }
    found.push_back({path, blends, &raw, material});
    return;
  }
  // A malformed soft_blend is left to fieldlib's loader, which says what is wrong.
  if (!raw.contains("children") || !raw.at("children").is_array()) return;
  const std::vector<Params> children = p.objects("children");
  blends.push_back(&raw);
  for (size_t i = 0; i < children.size(); ++i) {
    path.push_back(i);
    collect(children[i], path, blends, materials, found);
    path.pop_back();
  }
  blends.pop_back();
}

// The component alone, inside copies of its soft_blends that keep only it: Σ of one term is the
// term, and the soft_blends' placements still apply.
json alone(const Found& f) {
  json node = *f.node;
  node.erase("material");
  for (auto it = f.blends.rbegin(); it != f.blends.rend(); ++it) {
    json blend = **it;
    blend["children"] = json::array({std::move(node)});
    node = std::move(blend);
  }
  return node;
}

}  // namespace

void ComponentMaterials::weights(const Vec3& p, std::vector<Weight>& out) const {
  out.clear();
  double total = 0;
  for (const Component& c : components_) {
    if (!c.support.contains(p)) continue;
    // POV-Ray's weight: the component's own field value s_i f_i(p), taken absolutely.
    const double w = std::abs(c.field->value(p));
    if (!(w > 0)) continue;
    total += w;
    bool merged = false;
    for (Weight& e : out)
      if (e.material == c.material) {
        e.weight += w;
        merged = true;
        break;
      }
    if (!merged) out.push_back({c.material, w});
  }
  for (Weight& e : out) e.weight /= total;
}

NodePtr build_object_field(const Params& field, const BuildContext& ctx,
                           const Material& object_material,
                           std::shared_ptr<const ComponentMaterials>* components) {
  components->reset();
  std::vector<Material> materials{object_material};
  std::vector<Found> found;
  std::vector<size_t> path;
  std::vector<const json*> blends;
  if (type_of(field.raw()) == "soft_blend") collect(field, path, blends, materials, found);
  if (materials.size() == 1) return build_field(field, ctx);

  // fieldlib builds the field without the materials; errors keep their pointers (only the
  // "material" keys are gone).
  json stripped = field.raw();
  for (const Found& f : found) {
    json* node = &stripped;
    for (size_t i : f.path) node = &(*node)["children"][i];
    node->erase("material");
  }
  NodePtr built = build_field(Params(stripped, field.pointer(), field.file()), ctx);

  auto out = std::make_shared<ComponentMaterials>();
  out->materials_ = std::move(materials);
  for (const Found& f : found) {
    const json one = alone(f);
    NodePtr node = build_field(Params(one, field.pointer(), field.file()), ctx);
    // The support: where s f > 0 for a positive strength, s f < 0 for a negative one.
    const double s = f.node->value("strength", 1.0);
    const Box support =
        s > 0 ? node->region(1e-300, Side::Above) : node->region(-1e-300, Side::Below);
    out->components_.push_back(
        {std::move(node), support.bounded() ? support : Box::unbounded(), f.material});
  }
  *components = std::move(out);
  return built;
}

}  // namespace softtrace

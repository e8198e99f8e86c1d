#include "scene/component_materials.h"

#include <cmath>
#include <string>
#include <unordered_map>

#include "describe/kind_info.h"
#include "eval/eval.h"
#include "model/program_builder.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

// A component found under the soft_blends: where it is (child indices from the field's root) and
// its material.
struct Found {
  std::vector<size_t> path;
  int material;
};

// The node's "type" (empty when it has none that is a string), found once and not copied: every
// component of a blend is asked.
const std::string& type_of(const json& node) {
  static const std::string none;
  if (!node.is_object()) return none;
  const auto it = node.find("type");
  return it != node.end() && it->is_string() ? it->get_ref<const std::string&>() : none;
}

// Walks the soft_blends from `p`, reading each soft_object child's "material" into `materials`.
void collect(const Params& p, std::vector<size_t>& path, std::vector<Material>& materials,
             std::vector<Found>& found) {
  const json& raw = p.raw();
  if (type_of(raw) != "soft_blend") {
    int material = 0;
    if (type_of(raw) == "soft_object" && p.has("material")) {
      materials.push_back(load_material(p.object("material")));
      material = static_cast<int>(materials.size()) - 1;
    }
    found.push_back({path, material});
    return;
  }
  // A malformed soft_blend is left to fieldlib's loader, which says what is wrong.
  if (!raw.contains("children") || !raw.at("children").is_array()) return;
  const json& children = raw.at("children");
  for (const json& c : children)
    if (!c.is_object()) p.objects("children");  // its located error, before any child's
  for (size_t i = 0; i < children.size(); ++i) {
    path.push_back(i);
    const json& c = children[i];
    const std::string& type = type_of(c);
    // A component without a material of its own is recorded as collect would record it, without
    // a Params and its pointer for each of a large blend's components.
    if (type == "soft_blend" || (type == "soft_object" && c.contains("material")))
      collect(Params(c, p.pointer() + "/children/" + std::to_string(i), p.file()), path, materials,
              found);
    else
      found.push_back({path, 0});
    path.pop_back();
  }
}

// Whether collect, from the soft_blend `blend`, would find no material and raise no error: no
// soft_object under the soft_blends has a "material", and no soft_blend's children hold a
// non-object (collect's located error). The same walk without its Params and without a copy of
// the path for each component (a blend of 1000 plain components spent 1.07 M instructions in
// collect for a list it then dropped), each child's members read in one pass by their names'
// letters (two searches of its map compared the keys through strlen and memcmp at every step).
bool plain(const json& blend) {
  const auto children = blend.find("children");
  if (children == blend.end() || !children->is_array()) return true;
  for (const json& c : *children)
    if (!c.is_object()) return false;
  for (const json& c : *children) {
    bool blend_child = false, object = false, material = false;
    for (auto m = c.begin(); m != c.end(); ++m) {
      if (same_name(m.key(), "material")) material = true;
      if (!same_name(m.key(), "type") || !m->is_string()) continue;
      const std::string& type = m->get_ref<const std::string&>();
      blend_child = same_name(type, "soft_blend");
      object = same_name(type, "soft_object");
    }
    if (blend_child ? !plain(c) : object && material) return false;
  }
  return true;
}

// Records the nodes that fieldlib builds from the components' JSON objects (by address).
class FindComponents final : public BuildObserver {
 public:
  explicit FindComponents(const std::vector<const json*>& objects) : nodes_(objects.size()) {
    for (size_t i = 0; i < objects.size(); ++i) index_[objects[i]] = i;
  }
  void built(const Params& p, const FieldNode& node) override {
    const auto it = index_.find(&p.raw());
    if (it != index_.end()) nodes_[it->second] = &node;
  }
  const std::vector<const FieldNode*>& nodes() const { return nodes_; }

 private:
  std::unordered_map<const json*, size_t> index_;
  std::vector<const FieldNode*> nodes_;
};

}  // namespace

void ComponentMaterials::weights(const double* terms, std::vector<Weight>& out) const {
  out.clear();
  double total = 0;
  for (size_t i = 0; i < material_of_.size(); ++i) {
    // POV-Ray's weight: the component's own field value s_i f_i(p), taken absolutely.
    const double w = std::abs(terms[i]);
    if (!(w > 0)) continue;
    total += w;
    bool merged = false;
    for (Weight& e : out)
      if (e.material == material_of_[i]) {
        e.weight += w;
        merged = true;
        break;
      }
    if (!merged) out.push_back({material_of_[i], w});
  }
  for (Weight& e : out) e.weight /= total;
}

void ComponentMaterials::weights(const Vec3& p, std::vector<Weight>& out) const {
  thread_local Workspace ws;
  thread_local std::vector<double> terms;
  terms.resize(material_of_.size());
  gradient_terms(*program_, p, nullptr, terms.data(), ws);
  weights(terms.data(), out);
}

NodePtr build_object_field(const Params& field, const BuildContext& ctx,
                           const Material& object_material,
                           std::shared_ptr<const ComponentMaterials>* components) {
  components->reset();
  std::vector<Material> materials{object_material};
  std::vector<Found> found;
  std::vector<size_t> path;
  if (type_of(field.raw()) == "soft_blend" && !plain(field.raw()))
    collect(field, path, materials, found);
  if (materials.size() == 1) return build_field(field, ctx);

  // fieldlib builds the field without the materials; errors keep their pointers (only the
  // "material" keys are gone). The components' nodes are found as they are built.
  json stripped = field.raw();
  std::vector<const json*> objects;
  for (const Found& f : found) {
    json* node = &stripped;
    for (size_t i : f.path) node = &(*node)["children"][i];
    node->erase("material");
    objects.push_back(node);
  }
  FindComponents finder(objects);
  BuildContext observed = ctx;
  observed.observer = &finder;
  NodePtr built = build_field(Params(stripped, field.pointer(), field.file()), observed);

  auto out = std::make_shared<ComponentMaterials>();
  out->materials_ = std::move(materials);
  for (const Found& f : found) out->material_of_.push_back(f.material);
  out->program_ = std::make_shared<const Program>(compile(*built, finder.nodes()));
  *components = std::move(out);
  return built;
}

}  // namespace softtrace

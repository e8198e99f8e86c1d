#include <cmath>
#include <cstdio>

#include "describe/building.h"
#include "model/node.h"
#include "model/placement.h"
#include "model/potential.h"

namespace softtrace {

namespace {

std::string names_of(KindGroup group) {
  std::string s;
  for (const auto& k : kinds())
    if (k.group == group) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

const KindInfo& kind_of(const Params& p, KindGroup group, const char* what) {
  const std::string type = p.string("type");
  const KindInfo* kind = find_kind(type, group);
  if (!kind)
    p.fail("type", std::string("unknown ") + what + " '" + type +
                       "' (expected one of: " + names_of(group) + ")");
  return *kind;
}

const ParamSpec& slot_of(const BuildContext& ctx, const std::string& key) {
  const ParamSpec* spec = ctx.kind ? find_param(*ctx.kind, key) : nullptr;
  if (!spec) throw std::logic_error("no slot '" + key + "' in the kind being built");
  return *spec;
}

// Rotations are periodic: reduce the angle before it meets π, so that no finite angle overflows.
Mat3 rotation_of(const Params& r) {
  r.check_keys({"axis", "deg"});  // a misspelled key before a missing one, as everywhere
  const Vec3 axis = r.vec3("axis");
  r.check(length(axis) > 0 && std::isfinite(length(axis)), "axis", "expected a non-zero axis");
  return Mat3::rotation(axis, std::fmod(r.number("deg"), 360.0));
}

}  // namespace

void warn(const BuildContext& ctx, const std::string& line) {
  if (ctx.warn)
    ctx.warn(line);
  else
    std::fprintf(stderr, "softtrace: warning: %s\n", line.c_str());
}

PotentialPtr build_potential(const Params& p) {
  const KindInfo& kind = kind_of(p, KindGroup::Potential, "potential");
  check_params(kind, p, false);
  PotentialPtr P = kind.create_potential(p);
  p.finish();
  return P;
}

NodePtr build_radius_transform(const Params& r, NodePtr d, PotentialPtr P,
                               const BuildContext& ctx) {
  const KindInfo& kind = kind_of(r, KindGroup::RadiusTransform, "radius transform");
  check_params(kind, r, false);
  BuildContext inner = ctx;
  inner.kind = &kind;
  NodePtr node = kind.create_radius(r, std::move(d), std::move(P), inner);
  r.finish();
  return node;
}

NodePtr build_field(const Params& p, const BuildContext& ctx) {
  const KindInfo& kind = kind_of(p, KindGroup::Node, "node type");
  const Family wanted = resolve(ctx.slot, ctx.convention);
  const Family given = resolve(kind.family, ctx.convention);
  if (!fits(wanted, given))
    p.fail("", std::string("expected ") + family_phrase(wanted) + ", got '" + kind.name + "' (" +
                   family_phrase(given) + ")");
  if (ctx.depth >= kMaxFieldDepth)
    p.fail("", "field nodes nested deeper than " + std::to_string(kMaxFieldDepth) + " levels");
  check_params(kind, p, true);
  BuildContext inner = ctx;
  ++inner.depth;
  inner.kind = &kind;
  NodePtr node = kind.create_node(p, inner);

  const Vec3 translate = p.vec3("translate", {});
  if (p.has("translate"))
    for (int i = 0; i < 3; ++i)
      p.check(std::abs(translate[i]) <= kMaxMagnitude, "translate/" + std::to_string(i),
              "expected a number of magnitude at most 1e150 (docs/scene-format.md)");
  Mat3 rotation;
  bool rotated = false;
  if (p.has("rotate")) {
    const Params r = p.object("rotate");
    rotation = rotation_of(r);
    r.finish();
    rotated = true;
  }
  p.finish();
  if (rotated || translate.x != 0 || translate.y != 0 || translate.z != 0)
    node = place(std::move(node), rotation, translate);
  return node;
}

NodePtr build_node(const Params& p, const std::string& key, const BuildContext& ctx) {
  BuildContext inner = ctx;
  inner.slot = slot_of(ctx, key).slot;
  return build_field(p.object(key), inner);
}

std::vector<NodePtr> build_children(const Params& p, const std::string& key,
                                    const BuildContext& ctx) {
  BuildContext inner = ctx;
  inner.slot = slot_of(ctx, key).slot;
  std::vector<Params> items = p.objects(key);
  // The table's count was checked before `create`; this guards kinds built without the table.
  if (items.size() > kMaxChildren)
    p.fail(key, "expected at most " + std::to_string(kMaxChildren) + " children, got " +
                    std::to_string(items.size()));
  std::vector<NodePtr> out;
  out.reserve(items.size());
  for (const auto& item : items) out.push_back(build_field(item, inner));
  return out;
}

}  // namespace softtrace

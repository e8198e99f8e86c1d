#include <cmath>
#include <cstdio>

#include "describe/building.h"
#include "loader/placement_keys.h"
#include "model/node.h"
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
  NodePtr node = apply_placement(kind.create_node(p, inner), p, kind);
  p.finish();
  if (ctx.observer) ctx.observer->built(p, *node);
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

#include <cmath>
#include <cstdio>
#include <cstring>

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

// Warnings given on this thread: a node whose build warned is not copied to its siblings, whose
// own warnings would name their own places.
thread_local unsigned long warnings_given = 0;

// A node as its kind makes it, before its placement.
struct Unplaced {
  NodePtr node;
  const KindInfo* kind;
};

Unplaced build_unplaced(const Params& p, const BuildContext& ctx) {
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
  return {kind.create_node(p, inner), &kind};
}

NodePtr placed(Unplaced u, const Params& p, const BuildContext& ctx) {
  NodePtr node = apply_placement(std::move(u.node), p, *u.kind);
  p.finish();
  if (ctx.observer) ctx.observer->built(p, *node);
  return node;
}

// Whether a and b are the same JSON to the bit: nlohmann's == takes 2 for 2.0 and -0.0 for 0.0,
// which a kind may read apart (an integer parameter, a sign). Each value is read through its
// pointer, no checked accessor: every child of a cloud is compared member by member.
bool identical(const nlohmann::json& a, const nlohmann::json& b) {
  using json = nlohmann::json;
  if (a.type() != b.type()) return false;
  switch (a.type()) {
    case json::value_t::object: {
      const auto &x = *a.get_ptr<const json::object_t*>(), &y = *b.get_ptr<const json::object_t*>();
      if (x.size() != y.size()) return false;
      for (auto i = x.begin(), j = y.begin(); i != x.end(); ++i, ++j)
        if (i->first != j->first || !identical(i->second, j->second)) return false;
      return true;
    }
    case json::value_t::array: {
      const auto &x = *a.get_ptr<const json::array_t*>(), &y = *b.get_ptr<const json::array_t*>();
      if (x.size() != y.size()) return false;
      for (size_t i = 0; i < x.size(); ++i)
        if (!identical(x[i], y[i])) return false;
      return true;
    }
    case json::value_t::number_float:
      return std::memcmp(a.get_ptr<const double*>(), b.get_ptr<const double*>(), sizeof(double)) ==
             0;
    case json::value_t::number_integer:
      return *a.get_ptr<const json::number_integer_t*>() ==
             *b.get_ptr<const json::number_integer_t*>();
    case json::value_t::number_unsigned:
      return *a.get_ptr<const json::number_unsigned_t*>() ==
             *b.get_ptr<const json::number_unsigned_t*>();
    case json::value_t::string:
      return *a.get_ptr<const std::string*>() == *b.get_ptr<const std::string*>();
    case json::value_t::boolean:
    case json::value_t::null:
      return a == b;
    case json::value_t::binary:
    case json::value_t::discarded:
      return false;
  }
  return false;
}

// Whether the node object `b` would build what `a` built as `kind` before its placement: the
// same members, each identical but the placement's, which build_unplaced does not read
// (check_params only names them; a kind's own "scale" is compared). `translate` is set to b's
// own "translate" member, or null where it has none: the copy's placement is read from it.
bool alike_but_placed(const nlohmann::json& a, const nlohmann::json& b, const KindInfo& kind,
                      const nlohmann::json** translate) {
  using json = nlohmann::json;
  *translate = nullptr;
  const auto *x = a.get_ptr<const json::object_t*>(), *y = b.get_ptr<const json::object_t*>();
  if (!x || !y || x->size() != y->size()) return false;
  for (auto i = x->begin(), j = y->begin(); i != x->end(); ++i, ++j) {
    const std::string& key = i->first;
    if (key != j->first) return false;
    const bool translation = same_name(key, "translate");
    if (translation) *translate = &j->second;
    if (identical(i->second, j->second)) continue;
    if (!(translation || is_placement_key(key)) || find_param(kind, key)) return false;
  }
  return true;
}

}  // namespace

void warn(const BuildContext& ctx, const std::string& line) {
  ++warnings_given;
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
  return placed(build_unplaced(p, ctx), p, ctx);
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
  // A cloud's components often differ only in their placement: where the next child is alike but
  // placed (every other member identical), a copy of this one's unplaced node is kept, and each
  // alike child after it is that copy placed by its own keys. Everything else the full build
  // does to such a child gives what it gave the first (the same members, kind and context), so
  // its errors are its placement's alone, at its own place, as the full build would give them.
  // Not where someone observes the nodes built, nor past a warning (each would name its child).
  NodePtr copy;
  const KindInfo* copy_kind = nullptr;
  const nlohmann::json* copy_of = nullptr;
  // The alike children have the copy's keys: whether `translate` is their one placement key is
  // asked once, of the copy's object.
  bool translated_only = false;
  const nlohmann::json* translate = nullptr;
  for (size_t i = 0; i < items.size(); ++i) {
    const Params& item = items[i];
    if (copy && alike_but_placed(*copy_of, item.raw(), *copy_kind, &translate)) {
      NodePtr node = copy->clone();
      if (!translated_only || !place_translated(node, translate))
        node = apply_placement(std::move(node), item, *copy_kind);
      out.push_back(std::move(node));
      continue;
    }
    copy = nullptr;
    const unsigned long warned = warnings_given;
    Unplaced u = build_unplaced(item, inner);
    const bool next_alike = !inner.observer && i + 1 < items.size() &&
                            alike_but_placed(item.raw(), items[i + 1].raw(), *u.kind, &translate);
    NodePtr kept = next_alike ? u.node->clone() : nullptr;
    const KindInfo* kind = u.kind;
    out.push_back(placed(std::move(u), item, inner));
    if (kept && warnings_given == warned) {
      copy = std::move(kept);
      copy_kind = kind;
      copy_of = &item.raw();
      translated_only = placed_by_translation_only(*copy_of, *kind);
    }
  }
  return out;
}

}  // namespace softtrace

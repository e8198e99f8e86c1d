// A node's placement keys (docs/scene-format.md "Placement"): `translate`, `rotate`, `scale` and
// `matrix`, read and checked for every node the registry builds.
#pragma once

#include "describe/kind_info.h"
#include "describe/params.h"
#include "model/node.h"

namespace softtrace {

// The placement keys above: check_params accepts them beside a kind's own parameters (and
// suggests them for a misspelled key); a blend's copied children may differ in them alone.
inline constexpr const char* kPlacementKeys[] = {"translate", "rotate", "scale", "matrix"};

inline bool is_placement_key(const std::string& key) {
  for (const char* name : kPlacementKeys)
    if (same_name(key, name)) return true;
  return false;
}

// `node` wrapped in the placement p describes (itself when p has none). `kind` is the node's:
// a kind with a parameter of its own named `scale` (offset) keeps that name.
NodePtr apply_placement(NodePtr node, const Params& p, const KindInfo& kind);

// Whether a node object `j` of `kind` has no placement key but `translate`, if that.
bool placed_by_translation_only(const nlohmann::json& j, const KindInfo& kind);

// apply_placement's answer for a node object whose one placement key is `translate` (its value
// `*translate`, or null where it has none: no placement), three numbers of magnitude at most
// 1e150, read from the JSON without a Params' records (a blend's copied component, whose other
// keys its first sibling's build has read); false, `node` left as it was, for any other
// translation, which apply_placement then builds or names the error of.
bool place_translated(NodePtr& node, const nlohmann::json* translate);

}  // namespace softtrace

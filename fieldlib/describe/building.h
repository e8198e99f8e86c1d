// What a kind's `create` function may ask for besides its own parameters: its nested nodes,
// potentials and radius transforms, built and checked as the loader builds every node. Declared
// here, below the model, so that node families need not include the loader; the loader's registry
// (loader/registry.cpp) defines them: the one place that turns scene type names into field nodes,
// potentials and radius transforms (pbrt's "parse → describe → create"). The kind comes from the
// table in loader/kinds.h, its parameters are checked against the table (unknown keys with a near
// miss first, then presence, types and ranges), the slot's family is checked, and only then does
// the kind's `create` read them. Placement (`translate`, `rotate`, `scale`, `matrix`) is read there
// for every node.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "describe/build_context.h"

namespace softtrace {

class FieldNode;
class Potential;
using NodePtr = std::unique_ptr<FieldNode>;
using PotentialPtr = std::unique_ptr<Potential>;

// Limits that keep hostile scenes from exhausting the stack (evaluation recurses through the
// tree, also on the renderer's worker threads, whose stacks may be smaller than the main thread's)
// or making every evaluation absurdly slow.
constexpr int kMaxFieldDepth = 256;
constexpr size_t kMaxChildren = 10000;

// Builds the node described by `p` (which must have "type") for the slot ctx.slot, wrapped in its
// placement.
NodePtr build_field(const Params& p, const BuildContext& ctx);
// Builds the node-valued parameter `key` of the kind being built (ctx.kind), for its slot family.
NodePtr build_node(const Params& p, const std::string& key, const BuildContext& ctx);
// Builds every element of the node-array parameter `key` of ctx.kind (count checked by the table).
std::vector<NodePtr> build_children(const Params& p, const std::string& key,
                                    const BuildContext& ctx);
// The potential named by p["type"].
PotentialPtr build_potential(const Params& p);
// The transformed soft object P(T(d)) for the radius transform described by `r`.
NodePtr build_radius_transform(const Params& r, NodePtr d, PotentialPtr P, const BuildContext& ctx);

// Checks `p` against `kind`'s parameters: unknown keys (with the nearest known name), then
// missing required ones, then each present one's type and range. `placement` allows the placement
// keys (translate, rotate, scale, matrix).
void check_params(const KindInfo& kind, const Params& p, bool placement);

// Reports a warning line through ctx.warn (or on stderr).
void warn(const BuildContext& ctx, const std::string& line);

}  // namespace softtrace

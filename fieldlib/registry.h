// The one place that turns scene type names into field nodes, potentials and radius transforms
// (pbrt's "parse → describe → create"): each kind's `create` reads its own parameters from a
// Params; placement (`translate`, `rotate`) and unknown-key checks happen here for every node.
#pragma once

#include <string>
#include <vector>

#include "node.h"
#include "params.h"

namespace softtrace {

// Limits that keep hostile scenes from exhausting the stack (evaluation recurses through the
// tree, also on TBB worker threads with small stacks) or making every evaluation absurdly slow.
constexpr int kMaxFieldDepth = 256;
constexpr size_t kMaxChildren = 10000;

struct BuildContext {
  Convention convention = Convention::Soft;
  int depth = 0;  // nodes above the one being built
};

struct NodeKind {
  const char* name;
  const char* family;   // "distance", "blend", "object"
  const char* summary;  // one line for --help and the README's node list
  NodePtr (*create)(const Params&, const BuildContext&);
};

const std::vector<NodeKind>& node_kinds();

// Builds the node described by `p` (which must have "type"), wrapped in its placement.
NodePtr build_field(const Params& p, const BuildContext& ctx);
// Builds every element of the array `key`; at least `min_count` of them.
std::vector<NodePtr> build_children(const Params& p, const std::string& key,
                                    const BuildContext& ctx, size_t min_count = 2);

}  // namespace softtrace

// A node's placement keys (docs/scene-format.md "Placement"): `translate`, `rotate`, `scale` and
// `matrix`, read and checked for every node the registry builds.
#pragma once

#include "describe/kind_info.h"
#include "describe/params.h"
#include "model/node.h"

namespace softtrace {

// `node` wrapped in the placement p describes (itself when p has none). `kind` is the node's:
// a kind with a parameter of its own named `scale` (offset) keeps that name.
NodePtr apply_placement(NodePtr node, const Params& p, const KindInfo& kind);

}  // namespace softtrace

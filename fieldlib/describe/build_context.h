// What a kind's `create` function is handed besides its parameters: where in the scene it is
// being built. Node-family headers declare their `create` functions with it, without the registry.
#pragma once

#include <string>

#include "describe/kind_info.h"
#include "describe/params.h"
#include "math/convention.h"

namespace softtrace {

class FieldNode;

// Told of each node built, after its placement, with the parameters it was built from (p.raw()
// is the JSON object's address): how a caller finds the node that one part of a field became
// (the renderer's component materials).
class BuildObserver {
 public:
  virtual void built(const Params& p, const FieldNode& node) = 0;

 protected:
  ~BuildObserver() = default;
};

struct BuildContext {
  Convention convention = Convention::Soft;
  int depth = 0;  // nodes above the one being built
  // The family the slot being filled takes: an object's field takes its convention's
  // (Family::ConventionField); a node built on its own anything.
  Family slot = Family::Any;
  // The kind being built (set for its `create`): its slots' families come from the table.
  const KindInfo* kind = nullptr;
  // The skeleton structure of the soft object's distance (modulation_check.h), while its radius
  // transform is built; empty when unknown.
  std::string skeleton;
  // Where warnings about an accepted scene go (one line each, located); stderr when null.
  void (*warn)(const std::string& line) = nullptr;
  // Told of every node built; null when nobody asks.
  BuildObserver* observer = nullptr;
};

}  // namespace softtrace

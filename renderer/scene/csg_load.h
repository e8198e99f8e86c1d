// Reading a CSG object (scene.h Csg, docs/scene-format.md "csg"): its operation, its operands and
// its box. The operands are objects of any form, read by the scene's own object loader.
#pragma once

#include <functional>

#include "scene/scene.h"

namespace softtrace {

// Reads one operand at `p` (its index among the operands), which inherits `inherited` as its
// material when it names none (null: nothing to inherit).
using OperandLoader =
    std::function<SceneObject(const Params& p, size_t index, const Material* inherited)>;

// Sets o.csg and o.bounds from `p`'s "csg" and "operands"; `passed_on` is the material the
// operands without one take (null: none). Throws SceneError at the pointer of a bad value: an
// unknown operation, fewer than two operands, a disc (it has no inside), or operands of an
// intersection whose boxes do not overlap, `cutaway_textures` on a union or merge, or cut objects
// showing more than one material under `cutaway_textures` (which gives the untextured parts, where
// no `passed_on` material reaches them, the material of what they cut).
void load_csg(const Params& p, SceneObject& o, const Material* passed_on,
              const OperandLoader& load_operand);

}  // namespace softtrace

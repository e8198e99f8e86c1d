// Reading a plain primitive (scene/primitive.h) from the scene file: kept apart from the struct,
// so that the tracer, which includes primitive.h, never compiles the JSON behind Params.
#pragma once

#include <string>

#include "describe/params.h"
#include "scene/primitive.h"

namespace softtrace {

// Reads the object's "shape" (its "type" and parameters, placement keys included). Throws
// SceneError at the pointer of a bad value.
Primitive load_primitive(const Params& p);

// Moves `s` by `m`, after its own placement: sets to_world, to_object and world_box. Returns why
// it cannot ("" when it can): a singular map, or a bounded shape placed beyond kMaxPosition.
std::string place_primitive(Primitive& s, const Affine& m);

}  // namespace softtrace

// Reading a plain primitive (scene/primitive.h) from the scene file: kept apart from the struct,
// so that the tracer, which includes primitive.h, never compiles the JSON behind Params.
#pragma once

#include "describe/params.h"
#include "scene/primitive.h"

namespace softtrace {

// Reads the object's "shape" (its "type" and parameters, placement keys included). Throws
// SceneError at the pointer of a bad value.
Primitive load_primitive(const Params& p);

}  // namespace softtrace

// The scene's objects as the tracers take them (trace_target.h), and back from a hit's face to
// the object or CSG operand it names, whose material shades it.
#pragma once

#include <vector>

#include "scene/scene.h"
#include "scene/trace_target.h"

namespace softtrace {

// A field object's solid: its field compiled, its global Lipschitz bound, iso, inside sign and
// bounds. `o` must have a field.
TraceTarget trace_target(const SceneObject& o);

// `o` as traced; a CSG's operands with it. Faces number `o` and its operands in depth-first
// order, `o` itself 0: face_object(o, face) finds them again.
TracedObject traced_object(const SceneObject& o);

// Every object of the scene, in order (the index of each is its Embree geometry's).
std::vector<TracedObject> traced_objects(const Scene& scene);

// The object or CSG operand that `face` (traced_object's numbering) names in `o`; `o` itself
// for a face that names nothing in it.
const SceneObject& face_object(const SceneObject& o, int face);

}  // namespace softtrace

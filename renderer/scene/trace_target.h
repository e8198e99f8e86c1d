// What the tracers (trace/) take of a scene object: plain data with no JSON and no loader, so
// that the tracer never sees the scene file. The scene layer builds it (traced_objects.h): a
// field's solid is a TraceTarget; a whole object, a field, a plain primitive or a CSG of such
// objects, is a TracedObject.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "math/box.h"
#include "program/program.h"
#include "scene/affine.h"
#include "scene/primitive.h"
#include "scene/triangle_mesh.h"

namespace softtrace {

// A field's solid: where inside_sign (f - iso) >= 0, within `bounds`.
struct TraceTarget {
  // f compiled (program/program.h), shared by the tracers of the solid and of its complement.
  std::shared_ptr<const Program> program;
  double lipschitz = 0;  // f's global Lipschitz bound (FieldNode::lipschitz; infinite: none)
  double iso = 0.5;
  // +1 where inside means f >= iso (soft), -1 where it means f <= iso (zero, constructive).
  double inside_sign = 1;
  Box bounds;  // where the surface is looked for: the object's "bounds" or the field's region
};

// POV-Ray's CSG operations (scene.h Csg).
enum class CsgOp { Union, Merge, Intersection, Difference };

// A scene object as the tracers see it: a field's solid, a plain primitive, a triangle mesh, or a
// CSG of objects.
struct TracedObject {
  // The scene layer's name for this object or CSG operand, which a CSG's hit reports for the
  // operand whose surface it is (its material is the face's); the tracers never read it.
  int face = -1;
  Box bounds;  // the object's box: Embree's, and where a CSG's spans are searched
  std::optional<TraceTarget> field;
  std::optional<Primitive> shape;
  // A mesh's triangles, shared with the loaded object (placed in the world, or in the enclosing
  // CSG's frame for an operand, which must then be closed: scene/mesh_closure.h).
  std::shared_ptr<const TriangleMesh> mesh;
  // A CSG (neither a field, a shape nor a mesh) has its operation and at least two operands.
  CsgOp op = CsgOp::Union;
  std::vector<TracedObject> operands;
  // A CSG's placement (scene.h Csg): its operands are in its own frame, which `to_parent` takes
  // to its parent's; `to_local` is the inverse of to_parent.linear. Not placed: the identity.
  bool placed = false;
  Affine to_parent;
  Mat3 to_local;
  bool csg() const { return !operands.empty(); }
};

}  // namespace softtrace

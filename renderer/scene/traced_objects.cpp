#include "scene/traced_objects.h"

#include "model/program_builder.h"

namespace softtrace {

namespace {

// `o` as traced, its face `next` and its operands' the ones after it, depth first.
TracedObject traced(const SceneObject& o, int& next) {
  TracedObject t;
  t.face = next++;
  t.bounds = o.bounds;
  if (o.field) t.field = trace_target(o);
  if (o.shape) t.shape = *o.shape;
  t.mesh = o.mesh;
  if (o.csg) {
    t.op = o.csg->op;
    t.placed = o.csg->placed;
    t.to_parent = o.csg->to_parent;
    t.to_local = o.csg->to_local;
    t.operands.reserve(o.csg->operands.size());
    for (const SceneObject& operand : o.csg->operands) t.operands.push_back(traced(operand, next));
  }
  return t;
}

// The object `face` names under `o`, whose own face is `at`; null if none (`at` is then past
// the faces of `o`'s tree).
const SceneObject* find(const SceneObject& o, int face, int& at) {
  if (at++ == face) return &o;
  if (o.csg)
    for (const SceneObject& operand : o.csg->operands)
      if (const SceneObject* found = find(operand, face, at)) return found;
  return nullptr;
}

}  // namespace

TraceTarget trace_target(const SceneObject& o) {
  TraceTarget t;
  // With component materials, the program that also reports the components' values.
  t.program =
      o.components ? o.components->program() : std::make_shared<const Program>(compile(*o.field));
  t.lipschitz = o.field->lipschitz();
  t.iso = o.iso;
  t.inside_sign = o.inside_sign;
  t.bounds = o.bounds;
  return t;
}

TracedObject traced_object(const SceneObject& o) {
  int next = 0;
  return traced(o, next);
}

std::vector<TracedObject> traced_objects(const Scene& scene) {
  std::vector<TracedObject> out;
  out.reserve(scene.objects.size());
  for (const SceneObject& o : scene.objects) out.push_back(traced_object(o));
  return out;
}

const SceneObject& face_object(const SceneObject& o, int face) {
  if (face <= 0) return o;  // the object itself, or no face (not a CSG's hit)
  int at = 0;
  const SceneObject* found = find(o, face, at);
  return found ? *found : o;
}

}  // namespace softtrace

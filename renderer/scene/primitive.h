// Plain primitives (docs/scene-format.md "shape"): POV-Ray's plane, box, sphere, cylinder, cone
// and disc as exact solids, placed by an affine map. The renderer traces them analytically
// (trace/primitive_trace.h), never as fields. Plain data: the tracer includes this, never the
// loader (primitive_load.h).
#pragma once

#include "math/box.h"
#include "scene/affine.h"

namespace softtrace {

struct Primitive {
  enum class Shape { Plane, Box, Sphere, Cylinder, Cone, Disc };
  Shape shape = Shape::Sphere;
  // In object space. Plane: inside is dot(normal, p) <= distance (normal unit). Box: lo..hi.
  // Sphere: center, radius. Cylinder and cone: the solid between the base (at a, radius r0) and
  // the cap (at b, radius r1), both capped (a cylinder has r0 = r1). Disc: center, normal (unit),
  // radius and hole radius (no inside: a flat surface).
  Vec3 a{0, 0, 0}, b{0, 0, 1};
  Vec3 normal{0, 0, 1};
  double distance = 0, r0 = 1, r1 = 1, hole = 0;
  Affine to_world;
  Mat3 to_object;  // the inverse of to_world.linear
  // to_world and to_object are the identity (place_primitive): the tracer takes the ray as it is.
  bool unplaced = false;
  // A plane's outward normal in the world, unit (place_primitive): the same on every hit, which
  // an unplaced plane (a floor, hit by most camera rays) takes from here.
  Vec3 world_normal{0, 0, 1};
  // Where the renderer looks for it: its box in the world, an infinite plane's clipped to within
  // kMaxPosition (the tracer drops hits beyond; seen from any eye within the scene's ranges, that
  // edge lies far below a pixel from the horizon).
  Box world_box;
};

// The name of each shape as the scene file writes it.
const char* shape_name(Primitive::Shape s);

}  // namespace softtrace

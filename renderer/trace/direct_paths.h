// Which scenes EmbreeScene traces without Embree, from what their objects are. The one rule read
// by EmbreeScene's build (embree_scene.cpp) and by the static softtrace, which cannot open Embree
// and hands a scene that needs it to softtrace-core as soon as the scene is loaded
// (cli/core_hand_over.h), before its fields are compiled and its tracers built.
#pragma once

#include <cstddef>

namespace softtrace {

// At most this many primitives beside one field are asked directly (EmbreeScene::Impl): each
// costs its exact test on every ray, where Embree's boxes would cull the bounded ones.
constexpr std::size_t kDirectPrimitives = 4;

// A scene's objects as the direct paths tell them apart.
struct ObjectKinds {
  int fields = 0;      // objects with a field
  int primitives = 0;  // plain primitives (a "shape")
  int others = 0;      // CSGs and meshes
};

// Whether the direct paths trace every ray that starts outside the solids: one field, alone or
// beside at most kDirectPrimitives primitives.
inline bool traced_directly(const ObjectKinds& kinds) {
  return kinds.fields == 1 && kinds.others == 0 &&
         kinds.primitives <= static_cast<int>(kDirectPrimitives);
}

// Whether EmbreeScene asks for an Embree device: for a scene the direct paths do not trace, or
// one whose rays may start inside a solid (`interiors`: a transparent material), which only
// Embree takes.
inline bool needs_embree_device(const ObjectKinds& kinds, bool interiors) {
  return !traced_directly(kinds) || interiors;
}

}  // namespace softtrace

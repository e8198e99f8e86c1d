// A surface's material: its colour and POV-Ray 3.7's finish terms (docs/math.md, "Finishes"),
// under the keys POV-Ray uses. Plain data, read by the scene loader and by any kind of object
// (soft objects, primitives) that carries a "material"; render/finish.* evaluates it.
#pragma once

#include "describe/params.h"
#include "math/vec.h"

namespace softtrace {

struct Material {
  Vec3 color{0.8, 0.8, 0.8};  // linear RGB: POV's pigment
  // Multiplies the scene's ambient lights (POV's ambient_light). 1, not POV's 0.1, and diffuse 1,
  // not POV's 0.6, so that a scene without these keys keeps its Lambert look.
  Vec3 ambient{1, 1, 1};
  double diffuse = 1;
  double brilliance = 1;  // the diffuse cosine's exponent
  double phong = 0, phong_size = 40;
  double specular = 0, roughness = 0.05;  // the specular exponent is 1 / roughness
  double metallic = 0;                    // 0: highlights take the light's colour; 1: the surface's
  Vec3 reflection{0, 0, 0};               // mirror reflection, per channel
  // POV's reflection { reflection_min, reflection fresnel on }: the mirror reflection runs from
  // reflection_min to `reflection` by the Fresnel reflectance F of the surface for `ior`:
  // F reflection + (1 - F) reflection_min (docs/math.md §12.6).
  bool fresnel = false;
  Vec3 reflection_min{0, 0, 0};
  bool conserve_energy = false;  // the transmitted light loses what is reflected
  // The pigment's filter and transmit (POV's rgbft): the share of the light behind that passes
  // tinted by `color`, and untinted. 0 and 0: opaque.
  double filter = 0, transmit = 0;
  double ior = 1;  // index of refraction of the interior (POV's interior { ior })
};

// Whether light passes through a material (POV-Ray then traces a transmitted ray).
inline bool transparent(const Material& m) {
  return m.filter > 0 || m.transmit > 0;
}

// Whether a reflection (a material's, or the weighted mix of a blend's) sends a mirror ray.
inline bool reflects(const Vec3& reflection) {
  return reflection.x > 0 || reflection.y > 0 || reflection.z > 0;
}

// The "material" object at `m` (its keys are scene_keys("material")); throws SceneError naming
// the key for a value out of range.
Material load_material(const Params& m);

}  // namespace softtrace

// A loaded scene (docs/scene-format.md): camera, image settings, lights and objects whose fields
// are built by fieldlib's registry. Loading validates everything; rendering never sees bad input.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "describe/building.h"
#include "model/node.h"
#include "scene/component_materials.h"
#include "scene/light.h"
#include "scene/material.h"
#include "scene/primitive.h"
#include "scene/sky.h"
#include "scene/trace_target.h"
#include "scene/triangle_mesh.h"

namespace softtrace {

// docs/scene-format.md "camera". A perspective camera's rays leave the eye; an orthographic one's
// leave the plane through the eye across the view, parallel, over the height the perspective
// view has at the target (2 |target - eye| tan(fov / 2)), as POV-Ray's `orthographic` with an
// `angle`. A thin lens (aperture > 0) moves each ray's origin across a disc of that diameter
// about its pinhole origin and aims it at the point the pinhole ray meets the plane in focus,
// `focal_distance` ahead along the view.
struct Camera {
  enum class Projection { Perspective, Orthographic };
  Vec3 eye, target, up{0, 0, 1};
  double fov = 30;  // vertical, degrees
  // The view's width / height; 0: the image's (square pixels). Another stretches the picture
  // across, as POV-Ray's right/up ratio does when it is not the image's.
  double aspect = 0;
  Projection projection = Projection::Perspective;
  double aperture = 0;        // the lens's diameter; 0: a pinhole
  double focal_distance = 0;  // along the view; 0: the target's
  int blur_samples = 16;      // with aperture > 0, a pixel takes at least this many samples
};

// Why `c` cannot be a camera, as {key, message} (the key "" when it is fine): the loader and the
// command line's --eye/--target/--fov refuse the same cameras with the same words.
struct CameraProblem {
  std::string key, message;
};
CameraProblem camera_problem(const Camera& c);
// `c.up` made unit length (a valid camera's cross products then cannot overflow).
void normalize_up(Camera& c);
// A camera that frames `box` (bounded, non-empty): looking at its centre from the front right,
// above, at the distance where its bounding sphere fills the narrower of the image's two fields
// of view (`aspect` = width / height).
Camera camera_framing(const Box& box, double aspect);

// A camera path (scene "animation"): `frames` frames numbered from 0, each a camera from
// `cameras` or, with no list, the scene's camera turned about `axis` (through the target) by
// degrees * frame / frames, so that a 360-degree turntable loops without repeating a frame.
struct Animation {
  int frames = 0;  // 0: no animation
  std::vector<Camera> cameras;
  Vec3 axis{0, 0, 1};
  double degrees = 360;
};

// docs/scene-format.md "image", "antialias": POV-Ray's adaptive anti-aliasing (+A, method 1).
// A pixel whose colour differs from a neighbour's by more than `threshold` (the sum of the
// absolute differences of R, G, B over the background and A) takes spp * depth^2 samples.
// R, G and B are compared gamma-encoded, c^(1/gamma) (POV-Ray's Antialias_Gamma).
struct Antialias {
  double threshold = -1;  // < 0: off
  int depth = 3;
  double gamma = 2.5;
  bool on() const { return threshold >= 0; }
};

// docs/scene-format.md "image", "ambient_occlusion": the ambient lights reach a shaded point in
// the fraction of `samples` rays over its hemisphere that leave it for `distance` unblocked.
struct AmbientOcclusion {
  int samples = 0;  // 0: off
  double distance = 0;
};

struct ImageSettings {
  int width = 640, height = 480, spp = 1;
  // POV-Ray's max_trace_level: the camera ray is level 1, each mirror reflection one more.
  int max_trace_level = 5;
  Antialias antialias;
  AmbientOcclusion occlusion;
};

struct Csg;

struct SceneObject {
  std::string name;
  Material material;
  Convention convention = Convention::Soft;
  double iso = 0.5;
  // +1 where inside means f >= iso (soft), -1 where it means f <= iso (zero, constructive).
  double inside_sign = 1;
  Box bounds;  // where the renderer looks for the surface: "bounds" or the field's region box
  NodePtr field;
  // The field's components' own materials, mixed at each shaded point; null when none has one.
  std::shared_ptr<const ComponentMaterials> components;
  // A plain primitive ("shape") instead of a field: then `field` is null and `bounds` its box.
  std::optional<Primitive> shape;
  // A CSG of other objects ("csg") instead: then `field` is null, there is no `shape`, and
  // `bounds` follow from the operands' (Csg).
  std::shared_ptr<const Csg> csg;
  // A triangle mesh ("mesh") instead: then there is no field, shape or csg, and `bounds` is the
  // placed mesh's box.
  std::shared_ptr<const TriangleMesh> mesh;
};

// docs/scene-format.md "csg": POV-Ray's union, merge, intersection and difference of objects,
// each a field, a shape or another CSG. The solid is the operands' solids combined (each field
// clipped by its `bounds`); union and merge are the same solid (POV-Ray's merge only drops the
// inner surfaces of transparent objects, and materials here are opaque). Its box: the union of
// the operands' (union, merge), their intersection (intersection), the first's (difference).
// An operand without a material takes the nearest enclosing CSG object's that has one, as a
// POV-Ray CSG's texture passes to its untextured parts: a cut face keeps the cutter's material,
// or with `cutaway_textures` (csg_load.h) the material of what it cuts.
// A CSG object's placement keys move the whole tree: its operands (and their boxes, a field's
// `bounds` included) are in the CSG's own frame, `to_parent` takes that frame to its parent's
// (the world's at the top), and the object's `bounds` are in the parent's frame.
struct Csg {
  using Op = CsgOp;  // trace_target.h: the tracer takes it too
  Op op = Op::Union;
  std::vector<SceneObject> operands;
  bool placed = false;  // false: the identity
  Affine to_parent;
  Mat3 to_local;  // the inverse of to_parent.linear
};
const char* csg_name(Csg::Op op);

// What a scene without a camera frames of object `o`: its finite part. An infinite plane frames
// nothing (nullopt), and neither does an object whose box reaches kMaxPosition (ranges.h): a
// CSG's box is built from its operands' own framing boxes instead, a union's from those that
// have one (a floor under a blob frames the blob), an intersection's as the intersection of
// those that have one cut to each plane operand's half-space (a blob cut by a plane: the box of
// the blob's box on the plane's inside), a difference's as its first operand's cut to the
// outside of each plane it takes away, a placed CSG's placed.
std::optional<Box> framing_box(const SceneObject& o);

struct Scene {
  std::string path;
  // The bytes parsed (the file's, or the text's), kept for file_hash(): only an EXR's header and
  // a render hash need it, so a PNG-only run never hashes them (0.4 ms for 319 KB of text).
  std::shared_ptr<const std::string> text;
  uint64_t file_hash() const;  // 64-bit FNV-1a of `text` (0 without text)
  // The text's JSON document (an nlohmann::json), freed with the scene rather than at the load's
  // end: a command-line render ends its process without the scene's destructor (cmd_render.cpp),
  // and freeing a 1000-component scene's document (some 15,000 blocks, then the C library's
  // merging of them when the compile next asked for a large block) was an eighth of the set-up's
  // instructions. The loader reads nothing from it after the load.
  std::shared_ptr<const void> document;
  Camera camera;
  Animation animation;
  bool default_lights = false;  // the lights follow the camera (no "lights" in the file)
  ImageSettings image;
  Vec3 background{0, 0, 0};
  // A gradient "background" instead of a colour: the sky is then part of the picture (A = 1).
  std::optional<SkyGradient> sky;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;
  // Some material lets light through (Material's filter or transmit, on an object, a CSG operand
  // or a component): shadow rays then pass through such surfaces, tinted. Set by the loader.
  bool transparent = false;

  Box bounds() const;  // union of the objects' boxes
  // With no "camera" in the file: the camera is camera_framing(the union of the objects'
  // framing_box).
  bool default_camera = false;
};

// Frames above 2^26 pixels are refused with a SceneError naming `name`'s /image: their film
// alone would need gigabytes. The command line's --width/--height and Python's render() both
// check here, so that they refuse the same frames with the same words.
void check_pixel_count(const ImageSettings& image, const std::string& name);

// Makes frame `frame` (0 <= frame < animation.frames) the scene's camera, once, from the loaded
// scene; default lights move with it. Throws SceneError naming /animation when the frame does not
// exist.
void set_frame(Scene& scene, int frame);

// Replaces the camera's eye, target or fov (those given), as `softtrace render --eye --target
// --fov` do after the frame is set; default lights follow. Throws std::invalid_argument naming the
// option (`--eye: expected ...`) for a camera the loader would refuse.
struct CameraOverride {
  std::optional<Vec3> eye, target;
  std::optional<double> fov;
};
void override_camera(Scene& scene, const CameraOverride& o);

// 64-bit FNV-1a of `bytes`, continuing from `hash`.
uint64_t fnv1a(const std::string& bytes, uint64_t hash = 0xcbf29ce484222325ULL);

// Throws SceneError with "file:line:col: ..." for syntax and "file: /pointer: ..." for meaning
// (and "path: ..." for a path with a NUL byte or a file that cannot be opened). Scene files are
// read up to kMaxSceneBytes (a 100,000-child scene is 7.7 MB); a folder, a larger or endless
// input is refused.
constexpr size_t kMaxSceneBytes = size_t(256) << 20;
Scene load_scene(const std::string& path);
Scene parse_scene(const std::string& text, const std::string& name);

}  // namespace softtrace

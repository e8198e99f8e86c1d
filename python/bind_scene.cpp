// softtrace._native.Scene: a scene parsed from JSON text, its settings read as plain values and
// set by replacing the scene (PyScene, bindings.h): a setting changes the JSON text and the
// whole text is parsed again, so that a set value is checked exactly as in a file, with the same
// located errors, and the scene hash is always that of the text rendered.
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.h"
#include "scene/json_text.h"
#include "scene/scene_keys.h"

namespace softtrace::python {

namespace {

using json = nlohmann::json;

py::list vec(const Vec3& v) {
  return py::cast(std::vector<double>{v[0], v[1], v[2]});
}

// Every key of the camera, so that `scene.camera = dict(scene.camera, fov=40)` keeps a lens or an
// orthographic view.
py::dict camera_of(const Camera& c) {
  const char* projection = "perspective";
  switch (c.projection) {
    case Camera::Projection::Perspective:
      break;
    case Camera::Projection::Orthographic:
      projection = "orthographic";
      break;
  }
  py::dict d(py::arg("projection") = projection, py::arg("eye") = vec(c.eye),
             py::arg("target") = vec(c.target), py::arg("up") = vec(c.up), py::arg("fov") = c.fov);
  if (c.aspect > 0) d["aspect"] = c.aspect;  // absent: the image's
  d["aperture"] = c.aperture;
  d["focal_distance"] = c.focal_distance;
  d["blur_samples"] = c.blur_samples;
  return d;
}

py::dict light_of(const Light& l) {
  py::dict d;
  switch (l.type) {
    case Light::Type::Directional:
      d["type"] = "directional";
      d["direction"] = vec(l.direction);
      d["shadows"] = l.shadows;
      break;
    case Light::Type::Point:
      d["type"] = "point";
      d["position"] = vec(l.position);
      d["shadows"] = l.shadows;
      break;
    case Light::Type::Spot:
      // The loaded spot keeps its unit axis and its angles' cosines; lights_of puts back the
      // point_at and angles the text gave.
      d["type"] = "spot";
      d["position"] = vec(l.position);
      d["point_at"] = vec(l.position + l.direction);
      d["radius"] = std::acos(l.cos_radius) * 180 / M_PI;
      d["falloff"] = std::acos(l.cos_falloff) * 180 / M_PI;
      d["tightness"] = l.tightness;
      d["shadows"] = l.shadows;
      break;
    case Light::Type::Ambient:
      d["type"] = "ambient";
      break;
  }
  if (l.fade_power > 0) {
    d["fade_distance"] = l.fade_distance;
    d["fade_power"] = l.fade_power;
  }
  if (l.has_area) {
    py::dict a(py::arg("axis1") = vec(l.area.axis1), py::arg("axis2") = vec(l.area.axis2),
               py::arg("size1") = l.area.size1, py::arg("size2") = l.area.size2,
               py::arg("jitter") = l.area.jitter);
    if (l.area.adaptive >= 0) a["adaptive"] = l.area.adaptive;
    d["area"] = a;
  }
  d["color"] = vec(l.color);
  d["intensity"] = l.intensity;
  return d;
}

// The scene's lights as the file's keys: those the text gives, as given (a spot's point_at and
// angles exactly), the others at the values loaded; the default lights when the text has none.
py::list lights_of(const PyScene& s) {
  py::list out;
  const json doc = s.scene->default_lights ? json() : parse_json_text(s.text, s.scene->path);
  for (size_t i = 0; i < s.scene->lights.size(); ++i) {
    py::dict d = light_of(s.scene->lights[i]);
    if (!s.scene->default_lights) {
      const py::dict given = py::module_::import("json").attr("loads")(doc["lights"][i].dump());
      for (const auto& [key, value] : given) {
        if (py::str(key).cast<std::string>() == "area")
          d["area"].cast<py::dict>().attr("update")(value);
        else
          d[key] = value;
      }
    }
    out.append(d);
  }
  return out;
}

// The scene with `key` of its JSON replaced by `value` (removed when None), parsed again.
void replace_key(PyScene& s, const std::string& key, const py::handle& value) {
  json doc = parse_json_text(s.text, s.scene->path);
  if (value.is_none())
    doc.erase(key);
  else
    doc[key] = json::parse(json_text_of(value));
  std::string text = doc.dump(1);
  auto scene = std::make_shared<const Scene>(parse_scene(text, s.scene->path));
  s.scene = std::move(scene);  // only now: a refused value leaves the scene as it was
  s.text = std::move(text);
}

// One entry of "image", the others kept.
void replace_image_entry(PyScene& s, const char* entry, int value) {
  const json doc = parse_json_text(s.text, s.scene->path);
  json image = doc.contains("image") ? doc["image"] : json::object();
  image[entry] = value;
  replace_key(s, "image", py::module_::import("json").attr("loads")(image.dump()));
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<PyScene, std::shared_ptr<PyScene>>(m, "Scene")
      .def(py::init([](std::string text, const std::string& name) {
             auto s = std::make_shared<PyScene>();
             s->scene = std::make_shared<const Scene>(parse_scene(text, name));
             s->text = std::move(text);
             return s;
           }),
           py::arg("text"), py::arg("name"))
      .def_property_readonly("path", [](const PyScene& s) { return s.scene->path; })
      .def_property_readonly("_bytes", [](const PyScene& s) { return py::bytes(s.text); })
      .def_property_readonly("hash", [](const PyScene& s) { return s.scene->file_hash(); })
      .def_property_readonly("objects",
                             [](const PyScene& s) {
                               std::vector<std::string> names;
                               for (const SceneObject& o : s.scene->objects)
                                 names.push_back(o.name);
                               return names;
                             })
      .def_property_readonly("frames", [](const PyScene& s) { return s.scene->animation.frames; })
      .def_property(
          "width", [](const PyScene& s) { return s.scene->image.width; },
          [](PyScene& s, int v) { replace_image_entry(s, "width", v); })
      .def_property(
          "height", [](const PyScene& s) { return s.scene->image.height; },
          [](PyScene& s, int v) { replace_image_entry(s, "height", v); })
      .def_property(
          "spp", [](const PyScene& s) { return s.scene->image.spp; },
          [](PyScene& s, int v) { replace_image_entry(s, "spp", v); })
      .def_property(
          "max_trace_level", [](const PyScene& s) { return s.scene->image.max_trace_level; },
          [](PyScene& s, int v) { replace_image_entry(s, "max_trace_level", v); })
      .def_property(
          "camera", [](const PyScene& s) { return camera_of(s.scene->camera); },
          [](PyScene& s, const py::object& v) { replace_key(s, "camera", v); })
      .def_property(
          "image",
          [](const PyScene& s) {
            const ImageSettings& i = s.scene->image;
            py::dict d(py::arg("width") = i.width, py::arg("height") = i.height,
                       py::arg("spp") = i.spp, py::arg("max_trace_level") = i.max_trace_level);
            // The sampling options the scene turned on (off has no value in the file).
            if (i.antialias.on())
              d["antialias"] = py::dict(py::arg("threshold") = i.antialias.threshold,
                                        py::arg("depth") = i.antialias.depth,
                                        py::arg("gamma") = i.antialias.gamma);
            if (i.occlusion.samples > 0)
              d["ambient_occlusion"] = py::dict(py::arg("samples") = i.occlusion.samples,
                                                py::arg("distance") = i.occlusion.distance);
            return d;
          },
          [](PyScene& s, const py::object& v) { replace_key(s, "image", v); })
      .def_property(
          "background",
          [](const PyScene& s) -> py::object {
            const std::optional<SkyGradient>& sky = s.scene->sky;
            if (!sky) return vec(s.scene->background);
            py::list gradient;
            gradient.append(vec(sky->bottom));
            gradient.append(vec(sky->top));
            return py::dict(py::arg("gradient") = gradient, py::arg("up") = vec(sky->up));
          },
          [](PyScene& s, const py::object& v) { replace_key(s, "background", v); })
      .def_property("lights", &lights_of,
                    [](PyScene& s, const py::object& v) { replace_key(s, "lights", v); })
      .def_property_readonly("default_lights",
                             [](const PyScene& s) { return s.scene->default_lights; });
  // The keys of the scene's own objects (camera, lights, material, shapes, ...): the package's
  // builders for them are made from these lists, as the nodes' are from the kinds table.
  m.def(
      "scene_keys",
      [] {
        py::list out;
        for (const SceneKeyList& list : scene_key_lists())
          out.append(py::make_tuple(list.name, list.keys));
        return out;
      },
      "The keys of each of the scene's own objects, as (name, keys) in docs/scene-format.md's "
      "order.");
}

}  // namespace softtrace::python

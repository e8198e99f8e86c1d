// softtrace._native.Field: a compiled field (an object's, or a node's from JSON text) evaluated
// over numpy arrays of points of any shape (..., 3), batched and in parallel with the GIL
// released. A field keeps its node's JSON text and convention, which is what it pickles as.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <stdexcept>

#include "bindings.h"
#include "eval/batch.h"
#include "loader/build.h"
#include "model/program_builder.h"
#include "render/threads.h"
#include "scene/json_text.h"

namespace softtrace::python {

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

const char* convention_name(Convention c) {
  switch (c) {
    case Convention::Soft:
      return "soft";
    case Convention::Zero:
      return "zero";
    case Convention::Constructive:
      return "constructive";
  }
  return "soft";
}

Convention convention_named(const std::string& name) {
  if (name == "soft") return Convention::Soft;
  if (name == "zero") return Convention::Zero;
  if (name == "constructive") return Convention::Constructive;
  throw std::invalid_argument("unknown convention '" + name +
                              "' (expected soft, zero or constructive)");
}

// A compiled field and what keeps its nodes alive (a scene, or a node built on its own).
struct Field {
  std::shared_ptr<const Scene> scene;
  NodePtr own;
  const FieldNode* root = nullptr;
  Program program;
  std::string json_text, name;  // the node, for pickling
  Convention convention = Convention::Soft;

  // Values with the points' shape but the last axis, and gradients of the points' shape.
  py::object eval(const Points& points, bool with_gradient) {
    if (points.ndim() < 1 || points.shape(points.ndim() - 1) != 3)
      throw std::invalid_argument("points must be an array of shape (..., 3)");
    const std::vector<ssize_t> shape(points.shape(), points.shape() + points.ndim());
    const size_t n = size_t(points.size() / 3);
    py::array_t<double> values(std::vector<ssize_t>(shape.begin(), shape.end() - 1));
    py::array_t<double> grads(with_gradient ? shape : std::vector<ssize_t>{0});
    const double* xyz = points.data();
    double* f = values.mutable_data();
    double* g = with_gradient ? grads.mutable_data() : nullptr;
    {
      py::gil_scoped_release release;
      const std::vector<size_t> order = spatial_order(xyz, n);
      // Ranges of batches on the worker threads, each with its thread's workspace (fitted to the
      // program by eval_ordered), as the tracer keeps one (trace/tracer.cpp).
      parallel_ranges((n + kBatch - 1) / kBatch, 256, [&](size_t begin, size_t end) {
        thread_local Workspace ws;
        eval_ordered(program, xyz, order, begin * kBatch, std::min(n, end * kBatch), f, g, ws);
      });
    }
    if (with_gradient) return py::make_tuple(values, grads);
    return std::move(values);
  }
};

std::unique_ptr<Field> field_of_scene(const PyScene& s, const std::string& object) {
  auto f = std::make_unique<Field>();
  const std::vector<SceneObject>& objects = s.scene->objects;
  // By default the first object with a field (a shape has none), as `softtrace eval`.
  size_t i = 0;
  while (i < objects.size() &&
         (object.empty() ? bool(objects[i].shape) : objects[i].name != object))
    ++i;
  if (i == objects.size())
    throw SceneError(s.scene->path + (object.empty()
                                          ? std::string(": no object has a field: there is "
                                                        "nothing to evaluate")
                                          : ": no object named '" + object + "'"));
  if (objects[i].shape)
    throw SceneError(s.scene->path + ": /objects/" + std::to_string(i) + ": a " +
                     shape_name(objects[i].shape->shape) + " shape, not a field");
  if (objects[i].csg)
    throw SceneError(s.scene->path + ": /objects/" + std::to_string(i) + ": a CSG (" +
                     csg_name(objects[i].csg->op) + "), not a field");
  if (objects[i].mesh)
    throw SceneError(s.scene->path + ": /objects/" + std::to_string(i) +
                     ": a triangle mesh, not a field");
  f->scene = s.scene;
  f->root = objects[i].field.get();
  f->program = compile(*f->root);
  f->json_text = parse_json_text(s.text, s.scene->path)["objects"][i]["field"].dump();
  f->name = s.scene->path + ": /objects/" + std::to_string(i) + "/field";
  f->convention = objects[i].convention;
  return f;
}

std::unique_ptr<Field> field_of_json(const std::string& text, const std::string& convention,
                                     const std::string& name) {
  auto f = std::make_unique<Field>();
  f->convention = convention_named(convention);
  f->own = build(Spec(parse_json_text(text, name)), f->convention, name);
  f->root = f->own.get();
  f->program = compile(*f->root);
  f->json_text = text;
  f->name = name;
  return f;
}

}  // namespace

void bind_field(py::module_& m) {
  py::class_<Field>(m, "Field")
      .def(py::init([](const PyScene& scene, const std::string& object) {
             return field_of_scene(scene, object);
           }),
           py::arg("scene"), py::arg("object"))
      .def(py::init(&field_of_json), py::arg("json"), py::arg("convention"), py::arg("name"))
      .def(
          "_eval", [](Field& f, const Points& p) { return f.eval(p, false); }, py::arg("points"))
      .def(
          "_gradient", [](Field& f, const Points& p) { return f.eval(p, true); }, py::arg("points"))
      .def_property_readonly("json", [](const Field& f) { return f.json_text; })
      .def_property_readonly("name", [](const Field& f) { return f.name; })
      .def_property_readonly("convention",
                             [](const Field& f) { return convention_name(f.convention); });
}

}  // namespace softtrace::python

// The Python module `softtrace`: scenes, fields evaluated over numpy arrays of points (batched,
// in parallel, without the GIL), rendering to numpy arrays and the list of kinds. Bad input raises
// softtrace.SceneError (a ValueError) with the located message the command line prints.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "batch.h"
#include "build.h"
#include "film.h"
#include "frame.h"
#include "frame_metadata.h"
#include "json_text.h"
#include "kinds.h"
#include "scene.h"

namespace py = pybind11;
using namespace softtrace;

void bind_mesh(py::module_& m);  // bind_mesh.cpp

namespace {

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A compiled field and what keeps its nodes alive (a scene, or a node built on its own).
struct Field {
  std::shared_ptr<const Scene> scene;
  NodePtr own;
  const FieldNode* root = nullptr;
  Program program;
  tbb::enumerable_thread_specific<Workspace> workspaces;

  void compile_root() { program = compile(*root); }

  // values (N,), and grads (N, 3) when with_gradient.
  py::object eval(const Points& points, bool with_gradient) {
    if (points.ndim() != 2 || points.shape(1) != 3)
      throw std::invalid_argument("points must be an array of shape (N, 3)");
    const size_t n = size_t(points.shape(0));
    py::array_t<double> values(n);
    py::array_t<double> grads(std::vector<size_t>{n, 3});
    const double* xyz = points.data();
    double* f = values.mutable_data();
    double* g = with_gradient ? grads.mutable_data() : nullptr;
    {
      py::gil_scoped_release release;
      const std::vector<size_t> order = spatial_order(xyz, n);
      tbb::parallel_for(tbb::blocked_range<size_t>(0, (n + kBatch - 1) / kBatch, 256),
                        [&](const tbb::blocked_range<size_t>& r) {
                          eval_ordered(program, xyz, order, r.begin() * kBatch,
                                       std::min(n, r.end() * kBatch), f, g, workspaces.local());
                        });
    }
    if (with_gradient) return py::make_tuple(values, grads);
    return std::move(values);
  }
};

Convention convention_named(const std::string& name) {
  if (name == "soft") return Convention::Soft;
  if (name == "zero") return Convention::Zero;
  if (name == "constructive") return Convention::Constructive;
  throw std::invalid_argument("unknown convention '" + name +
                              "' (expected soft, zero or constructive)");
}

std::unique_ptr<Field> field_of_scene(std::shared_ptr<const Scene> scene,
                                      const std::string& object) {
  auto f = std::make_unique<Field>();
  for (const SceneObject& o : scene->objects)
    if (object.empty() || o.name == object) {
      f->root = o.field.get();
      break;
    }
  if (!f->root) throw SceneError(scene->path + ": no object named '" + object + "'");
  f->scene = std::move(scene);
  f->compile_root();
  return f;
}

std::unique_ptr<Field> field_of_json(const std::string& text, const std::string& convention,
                                     const std::string& name) {
  const Convention c = convention_named(convention);
  auto f = std::make_unique<Field>();
  f->own = build(Spec(parse_json_text(text, name)), c, name);
  f->root = f->own.get();
  f->compile_root();
  return f;
}

py::array_t<float> render(const Scene& loaded, int width, int height, int spp,
                          const std::vector<std::string>& outputs, bool flatten) {
  if (width < 0 || height < 0 || spp < 0 || width > 16384 || height > 16384 || spp > 4096)
    throw std::invalid_argument("width and height must be in [1, 16384] and spp in [1, 4096]");
  // The scene's camera and objects, at the size asked for.
  Scene& scene = const_cast<Scene&>(loaded);
  const ImageSettings saved = scene.image;
  if (width) scene.image.width = width;
  if (height) scene.image.height = height;
  if (spp) scene.image.spp = spp;
  const int w = scene.image.width, h = scene.image.height;
  Film film(w, h, AovSelection{});
  try {
    for (const auto& o : outputs) check_image_output_path(o);  // before the work, as the CLI
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    const TracedScene rt(scene, LipschitzMode::Local);
    render_frame(scene, rt, RenderOptions{}, film, nullptr, nullptr);
    // The files as `softtrace render -o` writes them: all or nothing.
    FrameInfo info = frame_info(scene, w, h);
    info.render_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    OutputOptions opt;
    opt.flatten = flatten;
    std::vector<std::string> temps;
    for (const auto& o : outputs) temps.push_back(write_image_temp(o, film, opt, info));
    for (size_t i = 0; i < outputs.size(); ++i) commit_image(temps[i], outputs[i]);
    forget_pending_writes();
  } catch (...) {
    abandon_pending_writes();
    forget_pending_writes();
    scene.image = saved;
    throw;
  }
  scene.image = saved;
  py::array_t<float> out(std::vector<size_t>{size_t(h), size_t(w), 4});
  std::copy(film.rgba.begin(), film.rgba.end(), out.mutable_data());
  return out;
}

py::list nodes() {
  static const char* const groups[] = {"node", "potential", "radius transform"};
  py::list out;
  for (const KindInfo& k : kinds()) {
    py::list params;
    for (const ParamSpec& p : k.params)
      params.append(py::dict(py::arg("name") = p.name, py::arg("type") = type_text(p),
                             py::arg("range") = range_text(p),
                             py::arg("default") = default_text(p)));
    out.append(py::dict(py::arg("name") = k.name, py::arg("group") = groups[int(k.group)],
                        py::arg("summary") = k.summary, py::arg("params") = params));
  }
  return out;
}

}  // namespace

PYBIND11_MODULE(softtrace, m) {
  m.doc() = "Implicit soft objects: load scenes, evaluate fields over numpy arrays, render.";
  py::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A loaded scene file")
      .def_property_readonly("path", [](const Scene& s) { return s.path; })
      .def_property_readonly("width", [](const Scene& s) { return s.image.width; })
      .def_property_readonly("height", [](const Scene& s) { return s.image.height; })
      .def_property_readonly("objects", [](const Scene& s) {
        std::vector<std::string> names;
        for (const SceneObject& o : s.objects) names.push_back(o.name);
        return names;
      });

  m.def(
      "load_scene",
      [](const std::string& path) { return std::make_shared<Scene>(load_scene(path)); },
      py::arg("path"), "Loads and validates a scene file; raises SceneError naming the place.");
  m.def(
      "parse_scene",
      [](const std::string& text, const std::string& name) {
        return std::make_shared<Scene>(parse_scene(text, name));
      },
      py::arg("text"), py::arg("name") = "<scene>", "A scene from JSON text.");

  py::class_<Field>(m, "Field", "A compiled field: an object's field, or a node from JSON text")
      .def(py::init([](std::shared_ptr<Scene> scene, const std::string& object) {
             return field_of_scene(std::move(scene), object);
           }),
           py::arg("scene"), py::arg("object") = "",
           "The field of the scene's object named `object` (default: the first).")
      .def(py::init(&field_of_json), py::arg("json"), py::arg("convention") = "soft",
           py::arg("name") = "<field>",
           "A node from its scene-format JSON text, checked for an object of `convention`.")
      .def(
          "eval", [](Field& f, const Points& p) { return f.eval(p, false); }, py::arg("points"),
          "Values at an (N, 3) array of points: an (N,) array.")
      .def(
          "gradient", [](Field& f, const Points& p) { return f.eval(p, true); }, py::arg("points"),
          "(values (N,), gradients (N, 3)) at an (N, 3) array of points.");

  m.def("render", &render, py::arg("scene"), py::arg("width") = 0, py::arg("height") = 0,
        py::arg("spp") = 0, py::arg("outputs") = std::vector<std::string>{},
        py::arg("flatten") = false,
        "Renders the scene's camera view: float32 (height, width, 4), premultiplied linear RGBA "
        "(as the EXR output). 0 keeps the scene's own size and samples. `outputs`: .exr/.png "
        "files written as `softtrace render -o` writes them (all or nothing; `flatten` as "
        "--flatten).");
  m.def("nodes", &nodes, "Every kind a scene may name, with its parameters.");
  bind_mesh(m);
  m.attr("__version__") = SOFTTRACE_VERSION;
}

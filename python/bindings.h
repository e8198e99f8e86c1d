// The pieces of the native module `softtrace._native`, each bound by its own file and called from
// module.cpp. The package `softtrace` (softtrace/__init__.py) puts Python signatures, docstrings
// and the dict-based helpers over them; the names here that start with "_" are for it alone.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "scene/scene.h"

namespace softtrace::python {

namespace py = pybind11;

// A scene as Python holds it, copied on write: `scene` is replaced, never changed, when a setting
// changes, so a render that took a reference keeps rendering the scene it started with, whatever
// other threads set meanwhile. `text` is the JSON that was parsed (what pickling and edits start
// from); scene->file_hash() is its hash.
struct PyScene {
  std::shared_ptr<const Scene> scene;
  std::string text;
};

// SceneError (a ValueError) with the attributes file, line, column, pointer and message, and a
// translator that raises it, text decoded leniently, for every softtrace::SceneError.
void bind_errors(py::module_& m);
void bind_scene(py::module_& m);
void bind_field(py::module_& m);
void bind_render(py::module_& m);
void bind_exr(py::module_& m);
void bind_mesh(py::module_& m);  // bind_mesh.cpp

// `value` (dicts, lists, tuples, numbers, strings, numpy arrays) as the JSON text the loader
// parses, through the package's softtrace._json.dumps; NaN and infinity are refused.
std::string json_text_of(const py::handle& value);

}  // namespace softtrace::python

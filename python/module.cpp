// The native module `softtrace._native`: scenes, fields evaluated over numpy arrays of points
// (batched, in parallel, without the GIL), rendering to numpy arrays, EXR files of named channels
// and the list of kinds. The package softtrace/ is the public face (signatures, docstrings,
// builders); bad input raises softtrace.SceneError with the located message the command line
// prints.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "loader/kinds.h"

namespace py = pybind11;
using namespace softtrace;

namespace {

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

PYBIND11_MODULE(_native, m) {
  m.doc() = "softtrace's native half; import softtrace, not this.";
  python::bind_errors(m);
  python::bind_scene(m);
  python::bind_field(m);
  python::bind_render(m);
  python::bind_exr(m);
  m.def("nodes", &nodes, "Every kind a scene may name, with its parameters.");
  python::bind_mesh(m);
  m.attr("__version__") = SOFTTRACE_VERSION;
}

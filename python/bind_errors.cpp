// softtrace.SceneError: the loader's one located line, and its parts as attributes, so that a
// program can point at the place without parsing the text. The message is decoded with
// backslash escapes: a syntax error quotes the bytes it stopped at, which need not be UTF-8,
// and a strict decode would lose the whole message.
#include <regex>

#include "bindings.h"

namespace softtrace::python {

namespace {

PyObject* g_scene_error = nullptr;  // the class; lives as long as the module

py::str lenient(const std::string& s) {
  return py::reinterpret_steal<py::str>(
      PyUnicode_DecodeUTF8(s.data(), Py_ssize_t(s.size()), "backslashreplace"));
}

// The loader's three forms: "file:LINE:COL: message" (syntax), "file: /pointer: message"
// (meaning) and "file: message".
void set_location(py::object& e, const std::string& what) {
  static const std::regex syntax(R"(^(.*?):(\d+):(\d+): ([\s\S]*)$)");
  static const std::regex meaning(R"(^(.*?): (/[^:]*): ([\s\S]*)$)");
  static const std::regex plain(R"(^(.*?): ([\s\S]*)$)");
  std::smatch m;
  if (std::regex_match(what, m, syntax)) {
    e.attr("file") = lenient(m[1]);
    e.attr("line") = std::stol(m[2]);
    e.attr("column") = std::stol(m[3]);
    e.attr("message") = lenient(m[4]);
  } else if (std::regex_match(what, m, meaning)) {
    e.attr("file") = lenient(m[1]);
    e.attr("pointer") = lenient(m[2]);
    e.attr("message") = lenient(m[3]);
  } else if (std::regex_match(what, m, plain)) {
    e.attr("file") = lenient(m[1]);
    e.attr("message") = lenient(m[2]);
  } else {
    e.attr("message") = lenient(what);
  }
}

}  // namespace

void bind_errors(py::module_& m) {
  static py::exception<SceneError> type(m, "SceneError", PyExc_ValueError);
  type.doc() =
      "A scene or field the loader refuses. str(e) is the located line the command line prints; "
      "file, line and column (syntax errors), pointer (a JSON pointer, for values) and message "
      "are its parts, None where the error has no such part.";
  for (const char* name : {"file", "line", "column", "pointer", "message"})
    type.attr(name) = py::none();
  g_scene_error = type.ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& error) {
      const std::string what = error.what();
      py::object e = py::reinterpret_borrow<py::object>(g_scene_error)(lenient(what));
      set_location(e, what);
      PyErr_SetObject(g_scene_error, e.ptr());
    }
  });
}

std::string json_text_of(const py::handle& value) {
  return py::module_::import("softtrace._json").attr("dumps")(value).cast<std::string>();
}

}  // namespace softtrace::python

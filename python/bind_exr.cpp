// EXR files of named float channels from and to numpy, through the renderer's OpenEXR code
// (image_file.h). Written all or nothing, as every output (output_file.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <set>
#include <stdexcept>

#include "bindings.h"
#include "io/image_file.h"
#include "io/image_io.h"
#include "io/output_file.h"

namespace softtrace::python {

namespace {

using Plane = py::array_t<float, py::array::c_style | py::array::forcecast>;

// The channels of render()'s arrays, as `softtrace render` names them in its EXR files.
std::vector<std::string> render_channels(const std::string& key) {
  if (key == "rgba") return {"R", "G", "B", "A"};
  if (key == "depth") return {"Z"};
  if (key == "normal") return {"N.X", "N.Y", "N.Z"};
  if (key == "steps") return {"steps"};
  if (key == "albedo") return {"albedo.R", "albedo.G", "albedo.B"};
  return {};
}

std::vector<std::string> split_names(const std::string& key) {
  std::vector<std::string> names;
  size_t start = 0;
  for (size_t comma; (comma = key.find(',', start)) != std::string::npos; start = comma + 1)
    names.push_back(key.substr(start, comma - start));
  names.push_back(key.substr(start));
  return names;
}

void write(const std::string& path, const py::dict& arrays,
           const std::map<std::string, std::string>& attributes) {
  static const char* const kExr[] = {".exr", nullptr};
  check_output_path(path, kExr);
  if (arrays.empty()) throw std::invalid_argument(path + ": no channels to write");
  ImageFile img;
  std::vector<Plane> planes;
  std::vector<std::vector<std::string>> names;
  std::set<std::string> seen;
  for (const auto& [key_handle, value] : arrays) {
    const std::string key = py::cast<std::string>(key_handle);
    Plane plane = Plane::ensure(value);
    if (!plane) throw std::invalid_argument(path + ": '" + key + "' is not an array of numbers");
    if (plane.ndim() != 2 && plane.ndim() != 3)
      throw std::invalid_argument(
          path + ": '" + key + "' must be of shape (height, width) or (height, width, channels)");
    const int h = int(plane.shape(0)), w = int(plane.shape(1));
    const size_t depth = plane.ndim() == 3 ? size_t(plane.shape(2)) : 1;
    std::vector<std::string> channels = render_channels(key);
    if (channels.size() != depth) channels = split_names(key);
    if (channels.size() != depth)
      throw std::invalid_argument(path + ": '" + key + "' names " +
                                  std::to_string(channels.size()) + " channels for an array of " +
                                  std::to_string(depth));
    if (planes.empty()) {
      if (h < 1 || w < 1) throw std::invalid_argument(path + ": an image of no pixels");
      img.full_width = img.width = w;
      img.full_height = img.height = h;
    } else if (h != img.height || w != img.width) {
      throw std::invalid_argument(path + ": '" + key + "' is " + std::to_string(h) + "x" +
                                  std::to_string(w) + ", the first array " +
                                  std::to_string(img.height) + "x" + std::to_string(img.width));
    }
    for (const std::string& c : channels)
      if (c.empty() || !seen.insert(c).second)
        throw std::invalid_argument(path + ": channel '" + c + "' is empty or named twice");
    planes.push_back(std::move(plane));
    names.push_back(std::move(channels));
  }
  for (const auto& n : names) img.channels.insert(img.channels.end(), n.begin(), n.end());
  const size_t nc = img.channels.size(), npix = size_t(img.width) * img.height;
  img.pixels.resize(npix * nc);
  size_t c0 = 0;
  for (size_t p = 0; p < planes.size(); ++p) {
    const float* in = planes[p].data();
    const size_t depth = names[p].size();
    for (size_t i = 0; i < npix; ++i)
      for (size_t k = 0; k < depth; ++k) img.pixels[i * nc + c0 + k] = in[i * depth + k];
    c0 += depth;
  }
  img.attributes = attributes;

  py::gil_scoped_release release;
  const std::string target = resolve_output_target(path);
  remove_stale_temporaries(target, process_start_time());
  try {
    const std::string tmp = create_pending_temp(target, path);
    try {
      write_exr(tmp, img);
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
    commit_temp(tmp, target, path);
    forget_pending_writes();
  } catch (...) {
    abandon_pending_writes();
    throw;
  }
}

py::dict read(const std::string& path) {
  ImageFile img;
  {
    py::gil_scoped_release release;
    img = read_exr(path);
  }
  py::dict out;
  const size_t nc = img.channels.size(), npix = size_t(img.width) * img.height;
  for (size_t c = 0; c < nc; ++c) {
    py::array_t<float> plane(std::vector<size_t>{size_t(img.height), size_t(img.width)});
    float* p = plane.mutable_data();
    for (size_t i = 0; i < npix; ++i) p[i] = img.pixels[i * nc + c];
    out[py::str(img.channels[c])] = plane;
  }
  return out;
}

}  // namespace

void bind_exr(py::module_& m) {
  m.def("write_exr", &write, py::arg("path"), py::arg("arrays"), py::arg("attributes"));
  m.def("read_exr", &read, py::arg("path"));
  m.def(
      "exr_attributes", [](const std::string& path) { return read_exr(path).attributes; },
      py::arg("path"));
}

}  // namespace softtrace::python

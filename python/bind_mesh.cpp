// softtrace.mesh and softtrace.write_mesh: the mesher (fieldlib/mesh) and the mesh files
// (renderer/io/mesh_file.h) over numpy arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "bindings.h"
#include "io/mesh_file.h"
#include "mesh/mesh.h"
#include "model/program_builder.h"
#include "scene/scene.h"
#include "scene/vertex_colors.h"

namespace py = pybind11;
using namespace softtrace;

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

py::array_t<double> vectors(const MeshArray<Vec3>& v) {
  py::array_t<double> out({py::ssize_t(v.size()), py::ssize_t(3)});
  double* p = out.mutable_data();
  for (size_t i = 0; i < v.size(); ++i)
    for (int a = 0; a < 3; ++a) p[3 * i + a] = v[i][a];
  return out;
}

std::tuple<py::array_t<double>, py::array_t<int64_t>, py::array_t<double>, py::array_t<double>>
mesh_scene(const std::shared_ptr<const Scene>& scene, const std::optional<std::string>& name,
           double voxel, int cells, const std::optional<std::vector<double>>& bounds, int threads) {
  const std::string object = name.value_or("");
  // By default the first object with a field (a shape has none).
  const SceneObject* obj = nullptr;
  for (const auto& o : scene->objects)
    if (!obj && o.field) obj = &o;
  if (!obj && !scene->objects.empty()) obj = &scene->objects.front();
  if (!object.empty()) {
    obj = nullptr;
    for (const auto& o : scene->objects)
      if (o.name == object) obj = &o;
    if (!obj) throw SceneError(scene->path + ": no object named '" + object + "'");
  }
  if (!obj) throw SceneError(scene->path + ": the scene has no object");
  if (obj->shape)
    throw SceneError(scene->path + ": object '" + obj->name + "' is a " +
                     shape_name(obj->shape->shape) + " shape, not a field");
  if (obj->csg)
    throw SceneError(scene->path + ": object '" + obj->name + "' is a CSG (" +
                     csg_name(obj->csg->op) + "), not a field");
  if (obj->mesh)
    throw SceneError(scene->path + ": object '" + obj->name + "' is a triangle mesh, not a field");
  Box region = obj->bounds;
  if (bounds) {
    const auto& b = *bounds;
    if (b.size() != 6) throw py::value_error("bounds: expected six numbers x0,x1,y0,y1,z0,z1");
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(b[2 * a]) || !std::isfinite(b[2 * a + 1]) || !(b[2 * a] < b[2 * a + 1]))
        throw py::value_error("bounds: each range must be finite with its lower end first");
    region = {{b[0], b[2], b[4]}, {b[1], b[3], b[5]}};
  }
  if (!region.bounded())
    throw py::value_error(scene->path + ": the object's region is unbounded; give bounds");
  if (voxel < 0 || !std::isfinite(voxel)) throw py::value_error("voxel must be positive");
  if (cells < 1 || cells > kMaxCells)
    throw py::value_error("cells must be between 1 and " + std::to_string(kMaxCells));
  const Program program = compile(*obj->field);
  MeshOptions opt;
  opt.voxel = voxel;
  opt.cells = cells;
  opt.threads = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  opt.color = obj->material.color;
  Mesh m;
  {
    py::gil_scoped_release release;
    try {
      m = mesh({&program, obj->iso, obj->inside_sign}, region, opt);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(e.what());
    }
    m.colors = vertex_colors(*obj, m.vertices, opt.threads);
  }
  py::array_t<int64_t> faces({py::ssize_t(m.faces.size()), py::ssize_t(3)});
  int64_t* f = faces.mutable_data();
  for (size_t i = 0; i < m.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) f[3 * i + k] = m.faces[i][k];
  return {vectors(m.vertices), faces, vectors(m.normals), vectors(m.colors)};
}

MeshArray<Vec3> read_vectors(const Doubles& a, const char* name, py::ssize_t rows) {
  if (a.ndim() != 2 || a.shape(1) != 3 || (rows >= 0 && a.shape(0) != rows))
    throw py::value_error(std::string(name) + ": expected an array of shape (" +
                          (rows >= 0 ? std::to_string(rows) : std::string("N")) + ", 3)");
  MeshArray<Vec3> v(size_t(a.shape(0)));
  const double* p = a.data();
  for (size_t i = 0; i < v.size(); ++i) v[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
  return v;
}

void write_mesh_file(const std::string& path, const Doubles& vertices, const Indices& faces,
                     const std::optional<Doubles>& normals, const std::optional<Doubles>& colors) {
  Mesh m;
  m.vertices = read_vectors(vertices, "vertices", -1);
  const auto nv = py::ssize_t(m.vertices.size());
  if (faces.ndim() != 2 || faces.shape(1) != 3)
    throw py::value_error("faces: expected an integer array of shape (F, 3)");
  const int64_t* f = faces.data();
  m.faces.resize(size_t(faces.shape(0)));
  for (size_t i = 0; i < m.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int64_t v = f[3 * i + k];
      if (v < 0 || v >= nv)
        throw py::value_error("faces[" + std::to_string(i) + "] names vertex " + std::to_string(v) +
                              " of " + std::to_string(nv));
      m.faces[i][k] = uint32_t(v);
    }
  if (normals) {
    m.normals = read_vectors(*normals, "normals", nv);
  } else {  // area-weighted face normals
    m.normals.assign(m.vertices.size(), Vec3{});
    for (const auto& t : m.faces) {
      const Vec3 n =
          cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
      for (uint32_t v : t) m.normals[v] += n;
    }
    for (Vec3& n : m.normals) n = length(n) > 0 ? normalize(n) : Vec3{0, 0, 1};
  }
  m.colors = colors ? read_vectors(*colors, "colors", nv)
                    : MeshArray<Vec3>(m.vertices.size(), Vec3{0.8, 0.8, 0.8});
  try {
    mesh_format(path);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  py::gil_scoped_release release;
  write_mesh(path, m);
}

}  // namespace

namespace softtrace::python {

void bind_mesh(py::module_& m) {
  const char* doc =
      "A closed, manifold, outward-oriented triangle mesh of an object's surface (softtrace "
      "mesh): (vertices (V, 3) float64, faces (F, 3) int64, unit normals (V, 3), linear RGB "
      "colours (V, 3)). `voxel` > 0 sets the cell size, else `cells` cells span the region's "
      "longest side; `bounds` [x0, x1, y0, y1, z0, z1] replaces the object's bounds (the mesh "
      "is capped where it cuts the solid).";
  m.def(
      "mesh",
      [](const python::PyScene& scene, const std::optional<std::string>& object, double voxel,
         int cells, const std::optional<std::vector<double>>& bounds,
         int threads) { return mesh_scene(scene.scene, object, voxel, cells, bounds, threads); },
      py::arg("scene"), py::arg("object") = py::none(), py::arg("voxel") = 0.0,
      py::arg("cells") = 128, py::arg("bounds") = py::none(), py::arg("threads") = 0, doc);
  m.def(
      "mesh",
      [](const std::string& path, const std::optional<std::string>& object, double voxel, int cells,
         const std::optional<std::vector<double>>& bounds, int threads) {
        return mesh_scene(std::make_shared<const Scene>(load_scene(path)), object, voxel, cells,
                          bounds, threads);
      },
      py::arg("scene"), py::arg("object") = py::none(), py::arg("voxel") = 0.0,
      py::arg("cells") = 128, py::arg("bounds") = py::none(), py::arg("threads") = 0,
      "The same from a scene file's path.");
  m.def("write_mesh", &write_mesh_file, py::arg("path"), py::arg("vertices"), py::arg("faces"),
        py::arg("normals") = py::none(), py::arg("colors") = py::none(),
        "Writes a mesh as .obj, .ply, .stl or .glb (as `softtrace mesh -o`), all or nothing. "
        "Missing normals are the faces' area-weighted normals; missing colours light grey.");
}

}  // namespace softtrace::python

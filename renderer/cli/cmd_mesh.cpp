// `softtrace mesh`: one object's surface as a triangle mesh file (fieldlib/mesh, io/mesh_file.h).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>

#include "cli/commands.h"
#include "io/mesh_file.h"
#include "io/output_file.h"
#include "mesh/mesh.h"
#include "model/program_builder.h"
#include "render/progress.h"
#include "scene/scene.h"
#include "scene/vertex_colors.h"

namespace softtrace {
namespace {

// "--bounds x0,x1,y0,y1,z0,z1": six finite numbers, each lower below its upper.
Box parse_bounds(const std::string& text) {
  std::istringstream in(text);
  double v[6];
  char comma = ',';
  int n = 0;
  for (; n < 6 && comma == ',' && in >> v[n]; ++n)
    if (n < 5 && !(in >> comma)) break;
  std::string rest;
  if (n != 6 || comma != ',' || (in >> rest))
    throw std::invalid_argument("--bounds '" + text + "': expected six numbers x0,x1,y0,y1,z0,z1");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(v[2 * a]) || !std::isfinite(v[2 * a + 1]) || !(v[2 * a] < v[2 * a + 1]))
      throw std::invalid_argument("--bounds '" + text + "': the " + std::string(1, "xyz"[a]) +
                                  " range must be finite with its lower end first");
  return {{v[0], v[2], v[4]}, {v[1], v[3], v[5]}};
}

}  // namespace

int run_mesh(const MeshArgs& a) {
  try {
    check_output_path(a.output, kMeshExtensions);  // fail before the work, not after
    const Scene scene = load_scene(a.scene);
    size_t index = 0;  // by default the first object with a field (a shape or a CSG has none)
    while (index + 1 < scene.objects.size() && !scene.objects[index].field) ++index;
    if (!a.object.empty()) {
      index = scene.objects.size();
      for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].name == a.object) index = i;
      if (index == scene.objects.size())
        throw SceneError(a.scene + ": no object named '" + a.object + "'");
    }
    const SceneObject& obj = scene.objects[index];
    if (obj.shape)
      throw SceneError(a.scene + ": /objects/" + std::to_string(index) + ": a " +
                       shape_name(obj.shape->shape) + " shape, not a field: mesh a field object");
    if (obj.csg)
      throw SceneError(a.scene + ": /objects/" + std::to_string(index) + ": a CSG (" +
                       csg_name(obj.csg->op) + "), not a field: mesh a field object");
    if (obj.mesh)
      throw SceneError(a.scene + ": /objects/" + std::to_string(index) +
                       ": a triangle mesh already, not a field: mesh a field object");
    const Box region = a.bounds.empty() ? obj.bounds : parse_bounds(a.bounds);
    if (!region.bounded())
      throw SceneError(a.scene + ": /objects/" + std::to_string(index) +
                       ": the object's region is unbounded; give --bounds");

    const Program program = compile(*obj.field);
    MeshOptions opt;
    opt.voxel = a.voxel;
    opt.cells = a.cells;
    opt.threads =
        a.threads > 0 ? a.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    opt.color = obj.material.color;
    // The bar counts the lattice's cells (millions per second as the rate).
    const double longest = std::max({region.extent().x, region.extent().y, region.extent().z});
    const double h = a.voxel > 0 ? a.voxel : longest / a.cells;
    double cells = 1;
    for (int i = 0; i < 3; ++i) cells *= std::max(1.0, std::ceil(region.extent()[i] / h)) + 1;
    const long total = long(std::min(cells, 1e15));
    Progress progress("meshing", total, !a.quiet && (a.progress || ::isatty(2)), 1, "Mcells/s");
    std::mutex mutex;
    long shown = 0;
    opt.progress = [&](double fraction) {
      std::lock_guard<std::mutex> lock(mutex);
      const long now = long(fraction * double(total));
      if (now > shown) progress.advance(now - shown), shown = now;
    };
    const auto start = std::chrono::steady_clock::now();
    Mesh m;
    try {
      m = mesh({&program, obj.iso, obj.inside_sign}, region, opt);
    } catch (const std::invalid_argument& e) {  // the lattice the options ask for
      throw std::invalid_argument((a.voxel > 0 ? "--voxel " + std::to_string(a.voxel)
                                               : "--cells " + std::to_string(a.cells)) +
                                  ": " + e.what());
    }
    m.colors = vertex_colors(obj, m.vertices, opt.threads);
    progress.finish();
    if (m.faces.empty())
      throw std::invalid_argument(a.scene + ": object '" + obj.name +
                                  "' has no surface in the region meshed; nothing written");
    write_mesh(a.output, m);
    if (!a.quiet) {
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const Vec3 e = m.lattice.extent();
      std::fprintf(stderr,
                   "%zu vertices, %zu faces, voxel %.6g (%ldx%ldx%ld cells) in %.2f s -> %s\n",
                   m.vertices.size(), m.faces.size(), m.voxel, std::lround(e.x / m.voxel),
                   std::lround(e.y / m.voxel), std::lround(e.z / m.voxel), secs, a.output.c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

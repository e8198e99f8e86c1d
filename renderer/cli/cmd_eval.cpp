#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "cli/commands.h"
#include "eval/eval.h"
#include "model/program_builder.h"
#include "scene/scene.h"

namespace softtrace {

namespace {

constexpr size_t kMaxLine = 4096;

}  // namespace

int run_eval(const EvalArgs& a) {
  try {
    const Scene scene = load_scene(a.scene);
    // By default the first object with a field (a shape or a CSG has none).
    const SceneObject* obj = nullptr;
    for (const auto& o : scene.objects)
      if (!obj && o.field) obj = &o;
    if (!obj && a.object.empty())
      throw SceneError(a.scene + ": no object has a field: there is nothing to evaluate");
    if (!a.object.empty()) {
      obj = nullptr;
      for (const auto& o : scene.objects)
        if (o.name == a.object) obj = &o;
      if (!obj) throw SceneError(a.scene + ": no object named '" + a.object + "'");
    }
    if (obj->shape)
      throw SceneError(a.scene + ": object '" + obj->name + "' is a " +
                       shape_name(obj->shape->shape) +
                       " shape, not a field: there is nothing to evaluate");
    if (obj->csg)
      throw SceneError(a.scene + ": object '" + obj->name + "' is a CSG (" +
                       csg_name(obj->csg->op) + "), not a field: there is nothing to evaluate");
    if (obj->mesh)
      throw SceneError(a.scene + ": object '" + obj->name +
                       "' is a triangle mesh, not a field: there is nothing to evaluate");
    // The library's evaluators on the object's compiled program, pruned to each point.
    const Program program = compile(*obj->field);
    Workspace ws;
    std::ifstream file;
    if (!a.points.empty()) {
      std::error_code ec;
      if (std::filesystem::is_directory(a.points, ec))
        throw SceneError(a.points + ": is a folder, not a points file");
      file.open(a.points);
      if (!file) throw SceneError(a.points + ": cannot open the points file");
    }
    std::istream& in = a.points.empty() ? std::cin : file;
    const std::string source = a.points.empty() ? "<stdin>" : a.points;

    // Lines are bounded (three %.17g numbers take under 80 bytes), so an endless line such as
    // /dev/zero's is refused at once instead of read into memory.
    std::vector<char> buffer(kMaxLine + 1);
    for (long n = 1;; ++n) {
      in.getline(buffer.data(), std::streamsize(buffer.size()));
      if (in.fail() && !in.eof() && size_t(in.gcount()) == kMaxLine)
        throw SceneError(source + ":" + std::to_string(n) + ": a line longer than " +
                         std::to_string(kMaxLine) + " bytes; expected 'x y z'");
      if (in.bad()) throw SceneError(source + ":" + std::to_string(n) + ": cannot read the file");
      if (in.gcount() == 0 && (in.eof() || in.fail())) break;
      const std::string line(buffer.data(), size_t(in.gcount()) - (in.eof() ? 0 : 1));
      std::istringstream ls(line);
      double x, y, z;
      std::string rest;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      if (!(ls >> x >> y >> z) || (ls >> rest) || !std::isfinite(x) || !std::isfinite(y) ||
          !std::isfinite(z))
        throw SceneError(source + ":" + std::to_string(n) +
                         ": expected three finite numbers 'x y z'");
      Vec3 g;
      const double v = evaluate(program, {x, y, z}, &g, ws);
      std::printf("%.17g %.17g %.17g %.17g\n", v, g.x, g.y, g.z);
      if (in.eof()) break;
    }
    return 0;
  } catch (const std::exception& e) {
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include "eval/eval.h"
#include "model/program_builder.h"
#include "scene/scene.h"

namespace softtrace {

int run_eval(const EvalArgs& a) {
  try {
    const Scene scene = load_scene(a.scene);
    const SceneObject* obj = &scene.objects.front();
    if (!a.object.empty()) {
      obj = nullptr;
      for (const auto& o : scene.objects)
        if (o.name == a.object) obj = &o;
      if (!obj) throw SceneError(a.scene + ": no object named '" + a.object + "'");
    }
    // The library's evaluators on the object's compiled program, pruned to each point.
    const Program program = compile(*obj->field);
    Workspace ws;
    std::ifstream file;
    if (!a.points.empty()) {
      file.open(a.points);
      if (!file) throw SceneError(a.points + ": cannot open the points file");
    }
    std::istream& in = a.points.empty() ? std::cin : file;
    const std::string source = a.points.empty() ? "<stdin>" : a.points;

    std::string line;
    for (long n = 1; std::getline(in, line); ++n) {
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
    }
    return 0;
  } catch (const std::exception& e) {
    report_error(e.what());
    return 2;
  }
}

}  // namespace softtrace

// Loads a scene file and prints its first object's field value at a point, through the renderer
// library's loader: `scene_value SCENE X Y Z`.
#include <softtrace/eval/eval.h>
#include <softtrace/model/program_builder.h>
#include <softtrace/scene/scene.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: scene_value SCENE X Y Z\n");
    return 2;
  }
  using namespace softtrace;
  try {
    const Scene scene = load_scene(argv[1]);
    const Program program = compile(*scene.objects.front().field);
    Workspace ws;
    const Vec3 p{std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4])};
    std::printf("%.17g\n", evaluate(program, p, nullptr, ws));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "softtrace: %s\n", e.what());
    return 2;
  }
  return 0;
}

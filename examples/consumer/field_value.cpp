// Builds two blended soft objects in code (no JSON) and prints the field's value at the point
// given on the command line, as `softtrace eval` prints it for two_blobs.json (the same field).
#include <softtrace/eval/eval.h>
#include <softtrace/loader/build.h>
#include <softtrace/model/program_builder.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: field_value X Y Z\n");
    return 2;
  }
  using namespace softtrace;
  try {
    const NodePtr field = build(soft_blend({
        soft_object(lp_metric({30, 30, 12}, 20), wyvill()),
        translate(soft_object(lp_metric({10, 10, 10}, 2), murakami()), {25, 0, 0}),
    }));
    const Program program = compile(*field);
    Workspace ws;
    const Vec3 p{std::atof(argv[1]), std::atof(argv[2]), std::atof(argv[3])};
    std::printf("%.17g\n", evaluate(program, p, nullptr, ws));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "field_value: %s\n", e.what());
    return 2;
  }
  return 0;
}

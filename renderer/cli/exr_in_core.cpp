// The static softtrace's read_exr and write_exr: EXR is softtrace-core's (through
// softtrace-exr.so, which a static program cannot open), so each hands the run over to it
// (core_hand_over.h). Linked ahead of the renderer library, as exr_on_demand.cpp is into
// softtrace-core, they keep exr_io.o and OpenEXR out of the program. load_exr_module, which a
// render with a default .exr output reaches after the load, execs softtrace-core itself: the
// static program's first throw costs 24 M instructions (core_hand_over.h).
#include <string>

#include "cli/core_hand_over.h"
#include "cli/exr_on_demand.h"
#include "io/image_io.h"

namespace softtrace {

void load_exr_module() {
  hand_over_to_core();
}

ImageFile read_exr(const std::string&) {
  throw NeedsCore{};
}

void write_exr(const std::string&, const ImageFile&, const ExrExtras&) {
  throw NeedsCore{};
}

}  // namespace softtrace

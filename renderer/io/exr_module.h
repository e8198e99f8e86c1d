// The EXR reader and writer as the command line loads them: `softtrace-exr.so`, a module beside
// softtrace-core, built from exr_io.cpp and linked to OpenEXR. OpenEXR's four libraries cost
// every process about 0.95 ms of CPU to load and relocate (3,700 of its 5,000 symbol
// relocations) while only an EXR output or input needs them; the command line opens the module
// at its first EXR (cli/exr_on_demand.cpp). Tests and the library link exr_io.cpp directly.
#pragma once

#include <string>

#include "io/image_file.h"

namespace softtrace {

struct ExrFunctions {
  ImageFile (*read)(const std::string& path);
  void (*write)(const std::string& path, const ImageFile& image, const ExrExtras& extras);
};

}  // namespace softtrace

// The module's one exported symbol.
extern "C" const softtrace::ExrFunctions* softtrace_exr_functions();

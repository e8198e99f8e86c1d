// The EXR reader and writer as the command line loads them: `softtrace-exr.so`, a module beside
// softtrace-core, built from exr_io.cpp and linked to OpenEXR. OpenEXR's four libraries cost
// every process about 0.95 ms of CPU to load and relocate (3,700 of its 5,000 symbol
// relocations) while only an EXR output or input needs them; the command line opens the module
// at its first EXR (cli/exr_on_demand.cpp). Tests and the library link exr_io.cpp directly.
#pragma once

#include <string>

#include "io/image_file.h"

namespace softtrace {

// softtrace-core carries its own copy of the C++ runtime (renderer/CMakeLists.txt) while the
// module, like OpenEXR, uses the shared one: two runtimes, so no C++ exception may cross between
// them (each has its own unwinder and type information). Each function catches every exception
// of its own and hands back its message, empty on success; the program throws its own
// std::runtime_error with it, the type exr_io.cpp throws. The strings, vectors and images handed
// across are allocated by one side and freed by the other: both runtimes' operator new and delete
// are malloc and free, the C library's, which the process has one of (nothing replaces it: no
// allocator proxy is linked or preloaded).
struct ExrFunctions {
  std::string (*read)(const std::string& path, ImageFile& image);
  std::string (*write)(const std::string& path, const ImageFile& image, const ExrExtras& extras);
};

}  // namespace softtrace

// The module's one exported symbol.
extern "C" const softtrace::ExrFunctions* softtrace_exr_functions();

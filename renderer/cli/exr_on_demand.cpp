// The command line's read_exr and write_exr: they open softtrace-exr.so, beside this program, at
// the first EXR and call its functions (io/exr_module.h). Linked into softtrace-core ahead of
// the renderer library, they keep its exr_io.o, and with it OpenEXR, out of the program.
#include "cli/exr_on_demand.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "io/exr_module.h"
#include "io/image_io.h"

namespace softtrace {

namespace {

// The folder of this program, as the launcher finds softtrace-core.
std::string module_path() {
  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path);
  std::string exe = n > 0 && n < static_cast<ssize_t>(sizeof path) ? std::string(path, n) : "";
  const size_t slash = exe.rfind('/');
  if (slash == std::string::npos) throw std::runtime_error("cannot find the folder of softtrace");
  return exe.substr(0, slash + 1) + "softtrace-exr.so";
}

const ExrFunctions& exr() {
  static const ExrFunctions* functions = nullptr;
  static std::string error;
  static std::once_flag once;
  std::call_once(once, [] {
    try {
      const std::string path = module_path();
      void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      const char* why = module ? nullptr : ::dlerror();
      const auto entry = module ? reinterpret_cast<const ExrFunctions* (*)()>(
                                      ::dlsym(module, "softtrace_exr_functions"))
                                : nullptr;
      if (module && !entry) why = ::dlerror();
      if (entry)
        functions = entry();
      else
        error = std::string("cannot load the EXR module: ") +
                (why ? why : (path + ": no entry point").c_str());
    } catch (const std::exception& e) {
      error = e.what();
    }
  });
  if (!functions) throw std::runtime_error(error);
  return *functions;
}

}  // namespace

void load_exr_module() {
  exr();
}

// The module's errors come back as messages (exr_module.h), thrown here as the program's own.
ImageFile read_exr(const std::string& path) {
  ImageFile image;
  const std::string error = exr().read(path, image);
  if (!error.empty()) throw std::runtime_error(error);
  return image;
}

void write_exr(const std::string& path, const ImageFile& image, const ExrExtras& extras) {
  const std::string error = exr().write(path, image, extras);
  if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace softtrace

// softtrace-exr.so's entry: exr_io.cpp's reader and writer (exr_module.h), each error handed back
// as its message rather than thrown across the module's boundary.
#include "io/exr_module.h"

#include <exception>

#include "io/image_io.h"

namespace softtrace {
namespace {

std::string read(const std::string& path, ImageFile& image) {
  try {
    image = read_exr(path);
    return {};
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an unknown error reading the EXR";
  }
}

std::string write(const std::string& path, const ImageFile& image, const ExrExtras& extras) {
  try {
    write_exr(path, image, extras);
    return {};
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an unknown error writing the EXR";
  }
}

}  // namespace
}  // namespace softtrace

extern "C" __attribute__((visibility("default"))) const softtrace::ExrFunctions*
softtrace_exr_functions() {
  static const softtrace::ExrFunctions functions{&softtrace::read, &softtrace::write};
  return &functions;
}

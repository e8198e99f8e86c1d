// softtrace-exr.so's entry: exr_io.cpp's reader and writer (exr_module.h).
#include "io/exr_module.h"

#include "io/image_io.h"

extern "C" __attribute__((visibility("default"))) const softtrace::ExrFunctions*
softtrace_exr_functions() {
  static const softtrace::ExrFunctions functions{&softtrace::read_exr, &softtrace::write_exr};
  return &functions;
}

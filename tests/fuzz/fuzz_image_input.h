// The image fuzzers' input: read_image reads files, so each input's bytes go to one file per
// process (/tmp/softtrace-fuzz-<name>-<pid>), are read back from there and the file is removed
// (libFuzzer may end the process without running static destructors, so none would clean up).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "io/image_file.h"

namespace softtrace {

class FuzzImageInput {
 public:
  explicit FuzzImageInput(const std::string& name)
      : path_("/tmp/softtrace-fuzz-" + name + "-" + std::to_string(::getpid())) {}

  // The image the bytes hold, into *img; false when they hold none (read_image's
  // std::runtime_error, the expected outcome for almost every input) or cannot be written.
  bool read(const uint8_t* data, size_t size, ImageFile* img) const {
    FILE* f = std::fopen(path_.c_str(), "wb");
    if (!f) return false;
    const bool written = std::fwrite(data, 1, size, f) == size;
    bool ok = std::fclose(f) == 0 && written;
    if (ok) {
      try {
        *img = read_image(path_);
      } catch (const std::runtime_error&) {
        ok = false;
      }
    }
    std::remove(path_.c_str());
    return ok;
  }

 private:
  std::string path_;
};

}  // namespace softtrace

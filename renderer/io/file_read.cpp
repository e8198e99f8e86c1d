#include "io/file_read.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

namespace softtrace {

void refuse_nul_in_path(const std::string& path) {
  if (path.find('\0') != std::string::npos)
    throw FileReadError(path.substr(0, path.find('\0')) + "...: a path with a NUL byte");
}

std::string read_file_bounded(const std::string& path, size_t limit, const std::string& what,
                              AtNul at_nul) {
  refuse_nul_in_path(path);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw FileReadError(path + ": is a folder, not a " + what + " file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileReadError(path + ": cannot open the " + what + " file");
  std::string bytes;
  // A regular file's size as the string's first capacity: grown by appends, a 222 KB scene was
  // copied again at 128 and 256 KB. Only a hint (no size for a device or a pipe, none beyond the
  // limit, which the read refuses): the read itself decides how much there is.
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size <= limit) bytes.reserve(size_t(size));
  // Left unset: each read writes what is then used. A vector's 64 KiB of zeros were 65,000 of a
  // 1x1 render's 1.41 M instructions, whatever the scene's size.
  constexpr size_t kBlockBytes = size_t(1) << 16;
  const std::unique_ptr<char[]> block(new char[kBlockBytes]);
  while (in) {
    in.read(block.get(), std::streamsize(kBlockBytes));
    const size_t got = size_t(in.gcount());
    bytes.append(block.get(), got);
    // memchr, not std::find: the C library's scans 32 bytes a step where std::find took ~3
    // instructions a byte (0.6 M of a 1000-component scene's load).
    if (at_nul == AtNul::Stop && std::memchr(block.get(), '\0', got) != nullptr) break;
    if (bytes.size() > limit)
      throw FileReadError(path + ": larger than " + std::to_string(limit >> 20) + " MiB; a " +
                          what + " file may be at most that");
  }
  if (in.bad()) throw FileReadError(path + ": cannot read the " + what + " file");
  return bytes;
}

}  // namespace softtrace

#include "cli/core_path.h"

#include <unistd.h>

#include <cstring>

namespace softtrace {

bool core_path(char* path, std::size_t size) {
  static const char kCore[] = "softtrace-core";
  if (size < 2) return false;
  // readlink does not terminate what it writes.
  const ssize_t n = ::readlink("/proc/self/exe", path, size - 1);
  if (n <= 0) return false;
  path[n] = '\0';
  char* slash = std::strrchr(path, '/');
  if (!slash || std::size_t(slash - path) + 1 + sizeof kCore > size) return false;
  std::memcpy(slash + 1, kCore, sizeof kCore);
  return true;
}

}  // namespace softtrace

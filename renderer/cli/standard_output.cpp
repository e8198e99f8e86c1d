#include "cli/standard_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace softtrace {

int checked_standard_output(int status, int failure_status) {
  errno = 0;
  // ferror: an earlier printf may have failed (a full buffer flushed mid-run) with nothing left
  // to flush now.
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return status;
  const int err = errno;
  std::fprintf(stderr, "softtrace: cannot write the standard output: %s\n",
               err ? std::strerror(err) : "write error");
  return failure_status;
}

}  // namespace softtrace

// `softtrace` where the build does not link statically (the sanitizer and fuzzer builds): blocks
// SIGINT and SIGTERM, then runs the renderer proper, `softtrace-core` in the same folder, with the
// same arguments. The renderer's shared libraries load before its main() can block anything; a
// signal then would kill it without a word. A signal mask survives exec, so a signal in that time
// waits for the renderer's handler (signals.h). Elsewhere `softtrace` is the static program
// (static_main.cpp), which serves the common render itself.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>

#include "cli/core_path.h"

int main(int, char** argv) {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigprocmask(SIG_BLOCK, &set, nullptr);

  char path[PATH_MAX];
  if (!softtrace::core_path(path, sizeof path)) {
    std::fprintf(stderr, "softtrace: cannot find the folder of this program\n");
    return 2;
  }
  ::execv(path, argv);
  std::fprintf(stderr, "softtrace: cannot run %s: %s\n", path, std::strerror(errno));
  return 2;
}

// `softtrace`: blocks SIGINT and SIGTERM, then runs the renderer proper, `softtrace-core` in the
// same folder, with the same arguments. The renderer's shared libraries (the C library and its
// maths library; OpenEXR and Embree, with the shared C++ runtime and TBB, are opened later, on
// demand) load before its main() can block anything; a signal then would kill it without a word.
// A signal mask survives exec, so a signal in that time waits for the renderer's handler
// (signals.h). Plain libc and linked statically where the build allows: this program's own
// start-up is the only unguarded moment. A static build normally never gets here:
// launcher_entry.cpp does the same before the C library starts, and only what it did not expect
// reaches main(), which then reports it.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>

int main(int, char** argv) {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigprocmask(SIG_BLOCK, &set, nullptr);

  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path);
  char* slash = n > 0 && n < static_cast<ssize_t>(sizeof path) ? std::strrchr(path, '/') : nullptr;
  static const char kCore[] = "softtrace-core";
  if (!slash || (slash - path) + 1 + sizeof kCore > sizeof path) {
    std::fprintf(stderr, "softtrace: cannot find the folder of this program\n");
    return 2;
  }
  std::memcpy(slash + 1, kCore, sizeof kCore);
  ::execv(path, argv);
  std::fprintf(stderr, "softtrace: cannot run %s: %s\n", path, std::strerror(errno));
  return 2;
}

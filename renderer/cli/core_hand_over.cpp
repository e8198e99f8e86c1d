#include "cli/core_hand_over.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>

#include "cli/core_path.h"
#include "cli/signals.h"
#include "scene/scene.h"
#include "trace/direct_paths.h"

namespace softtrace {

namespace {

// The memory file that stands for standard error, and standard error itself moved aside: both -1
// when nothing is held. Plain ints: the handler reads them on the thread they are written on.
int g_held = -1;
int g_stderr = -1;
// The static program's arguments, softtrace-core's; null in softtrace-core.
char** g_argv = nullptr;

void write_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    data += n;
    size -= size_t(n);
  }
}

// Puts standard error back; `keep` copies what was held to it first.
void end_hold(bool keep) {
  if (g_held < 0) return;
  if (keep) {
    char buffer[4096];
    for (off_t at = 0;;) {
      const ssize_t n = ::pread(g_held, buffer, sizeof buffer, at);
      if (n <= 0) break;
      write_all(g_stderr, buffer, size_t(n));
      at += n;
    }
  }
  ::dup2(g_stderr, STDERR_FILENO);
  ::close(g_stderr);
  ::close(g_held);
  g_held = g_stderr = -1;
}

}  // namespace

void hold_standard_error(char** argv) {
  g_argv = argv;
  // Close-on-exec: softtrace-core gets standard error, not these.
  int held = ::memfd_create("softtrace-stderr", MFD_CLOEXEC);
  // Without it (a kernel before 3.17, no descriptor left) the program prints as it goes, and a
  // hand-over after a warning would show that warning twice.
  if (held < 0) return;
  // Standard error closed (the file took its number): writes to it fail as they would have.
  if (held == STDERR_FILENO) {
    ::close(held);
    return;
  }
  // Standard input or output closed: the file moves above them, which stay closed.
  if (held < STDERR_FILENO) {
    const int moved = ::fcntl(held, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
    ::close(held);
    if (moved < 0) return;
    held = moved;
  }
  const int saved = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
  if (saved < 0 || ::dup2(held, STDERR_FILENO) < 0) {
    if (saved >= 0) ::close(saved);
    ::close(held);
    return;
  }
  g_held = held;
  g_stderr = saved;
}

void release_standard_error() {
  const sigset_t set = interrupt_signals();
  sigset_t old;
  pthread_sigmask(SIG_BLOCK, &set, &old);
  end_hold(/*keep=*/true);
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
}

void hand_over_to_core() {
  block_interrupts();
  std::fflush(stdout);  // nothing is written there before the decision; kept honest anyway
  char path[PATH_MAX];
  if (!core_path(path, sizeof path)) {
    end_hold(/*keep=*/true);
    std::fprintf(stderr, "softtrace: cannot find the folder of this program\n");
    ::_exit(2);
  }
  // softtrace-core gets standard error back and prints again what was held; the memory file
  // closes with the exec, and stays for the error below if the exec fails.
  if (g_held >= 0) ::dup2(g_stderr, STDERR_FILENO);
  ::execv(path, g_argv);
  const int error = errno;
  end_hold(/*keep=*/true);
  std::fprintf(stderr, "softtrace: EXR and Embree need %s: cannot run it: %s\n", path,
               std::strerror(error));
  ::_exit(2);
}

void hand_over_embree_scene(const Scene& scene) {
  if (!g_argv) return;
  // The kinds as traced_objects() makes them: a field object's tracer, a shape's primitive, and
  // a CSG's or a mesh's own geometry.
  ObjectKinds kinds;
  for (const SceneObject& o : scene.objects) {
    if (o.field)
      ++kinds.fields;
    else if (o.shape)
      ++kinds.primitives;
    else
      ++kinds.others;
  }
  if (needs_embree_device(kinds, scene.transparent)) hand_over_to_core();
}

}  // namespace softtrace

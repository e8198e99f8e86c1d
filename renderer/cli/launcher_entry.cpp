// The static softtrace's entry point (the build links it with `-e softtrace_launcher_entry`): it
// blocks SIGINT and SIGTERM by plain system calls before the C library starts, then either goes on
// to the C library's entry and static_main.cpp, which render and benchmark in this process, or
// execs softtrace-core beside it for what this program would only hand over later: every other
// command (diff and merge read EXR, and their few runs gain nothing from being served here; the
// help and the man page are softtrace-core's), and any argument that names an .exr file (an EXR
// output or a scene called so: softtrace-core serves both). Deciding here costs a comparison of
// the arguments, and spares those runs this program's C library start-up. That start-up asks the
// processor what it is, one `cpuid` at a time, and under a hypervisor each of them traps (0.66 ms
// of CPU here, KVM), which is why the exec comes before it. This path runs nothing of the C
// library: no stack protector (its canary lives in thread storage that is not set up yet), no
// library call (the compiler is told not to turn loops into memcpy), no pointer in static data.
// Anything it does not expect (an exec that fails, a path that does not fit, a secure-mode start)
// returns to the C library's own entry with the stack as the kernel gave it, and static_main.cpp
// runs the command here, handing over to softtrace-core where it must (core_hand_over.h).
#include <sys/syscall.h>

#include <climits>
#include <csignal>
#include <cstddef>

// What the entry calls runs before the C library too.
#define EARLY __attribute__((no_stack_protector, optimize("no-tree-loop-distribute-patterns")))

namespace {

long raw_syscall(long number, long a, long b, long c, long d = 0) {
  long result;
  register long r10 __asm__("r10") = d;
  __asm__ volatile("syscall"
                   : "=a"(result)
                   : "a"(number), "D"(a), "S"(b), "d"(c), "r"(r10)
                   : "rcx", "r11", "memory");
  return result;
}

constexpr long kAtNull = 0;
constexpr long kAtSecure = 23;  // AT_SECURE: the C library would clean the environment first

// Whether `s` is `word` (both null-terminated).
EARLY bool same(const char* s, const char* word) {
  while (*s && *s == *word) ++s, ++word;
  return *s == *word;
}

// Whether `s` ends in ".exr", in any case (as film.h's is_exr_path reads an output's extension).
EARLY bool ends_in_exr(const char* s) {
  const char* end = s;
  while (*end) ++end;
  if (end - s < 4 || end[-4] != '.') return false;
  return (end[-3] | 0x20) == 'e' && (end[-2] | 0x20) == 'x' && (end[-1] | 0x20) == 'r';
}

// Whether static_main.cpp serves the command line itself: a render or benchmark with no EXR named.
EARLY bool served_here(long argc, char** argv) {
  if (argc < 2 || !(same(argv[1], "render") || same(argv[1], "bench"))) return false;
  for (long i = 2; i < argc; ++i)
    if (ends_in_exr(argv[i])) return false;
  return true;
}

}  // namespace

// The kernel's stack at entry: argc, argv[0..argc-1], a null, the environment, a null, then the
// auxiliary vector's (type, value) pairs up to AT_NULL.
extern "C" __attribute__((used)) EARLY void softtrace_launch_early(long* stack) {
  const long argc = stack[0];
  char** argv = reinterpret_cast<char**>(stack + 1);
  char** envp = argv + argc + 1;
  char** end = envp;
  while (*end) ++end;
  for (const long* aux = reinterpret_cast<const long*>(end + 1); aux[0] != kAtNull; aux += 2)
    if (aux[0] == kAtSecure && aux[1] != 0) return;

  // The kernel's signal set is one 64-bit word here: bit n-1 for signal n.
  const unsigned long mask = (1ul << (SIGINT - 1)) | (1ul << (SIGTERM - 1));
  if (raw_syscall(SYS_rt_sigprocmask, SIG_BLOCK, reinterpret_cast<long>(&mask), 0, sizeof mask) !=
      0)
    return;
  if (served_here(argc, argv)) return;  // the C library starts with the signals blocked

  char path[PATH_MAX];
  const char self[] = "/proc/self/exe";
  const long n = raw_syscall(SYS_readlink, reinterpret_cast<long>(self),
                             reinterpret_cast<long>(path), sizeof path);
  if (n <= 0 || n >= static_cast<long>(sizeof path)) return;
  long slash = -1;
  for (long i = 0; i < n; ++i)
    if (path[i] == '/') slash = i;
  const char core[] = "softtrace-core";
  if (slash < 0 || static_cast<std::size_t>(slash) + 1 + sizeof core > sizeof path) return;
  for (std::size_t i = 0; i < sizeof core; ++i) path[slash + 1 + i] = core[i];
  raw_syscall(SYS_execve, reinterpret_cast<long>(path), reinterpret_cast<long>(argv),
              reinterpret_cast<long>(envp));
  // Only a failed exec gets here: static_main.cpp runs the command, and says why if it must hand it
  // over.
}

// %rdx holds the dynamic linker's finaliser for _start (none for a static program; kept anyway);
// %r12 is callee-saved, so it survives the call, and the call leaves %rsp where the kernel put it.
__asm__(
    ".text\n"
    ".globl softtrace_launcher_entry\n"
    ".type softtrace_launcher_entry, @function\n"
    "softtrace_launcher_entry:\n"
    "  mov %rdx, %r12\n"
    "  mov %rsp, %rdi\n"
    "  call softtrace_launch_early\n"
    "  mov %r12, %rdx\n"
    "  jmp _start\n"
    ".size softtrace_launcher_entry, . - softtrace_launcher_entry\n");

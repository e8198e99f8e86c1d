// cpu_has_avx2 (cpu_avx2.h).
#include "math/cpu_avx2.h"

#if __has_include(<sys/platform/x86.h>)  // glibc 2.33 and later
// A C header: its inline functions return _Bool, which GCC's C++ takes and Clang's does not.
#if defined(__clang__)
#define _Bool bool
#include <sys/platform/x86.h>
#undef _Bool
#else
#include <sys/platform/x86.h>
#endif
#define SOFTTRACE_GLIBC_CPU_FEATURES 1
#else
#include <cpuid.h>
#define SOFTTRACE_GLIBC_CPU_FEATURES 0
#endif

namespace softtrace {

bool cpu_has_avx2() {
  // Not __builtin_cpu_supports: it links libgcc's __cpu_indicator_init, a constructor that asks
  // the processor a dozen cpuid leaves at the start of every program linking fieldlib, and on a
  // virtual machine each cpuid traps to the hypervisor (30-45 us each on this project's KVM
  // guest: 0.2 ms of every softtrace run's start). glibc's dynamic loader has asked already, at
  // every start, and keeps the answer: AVX2 "active" is the CPU's AVX2 with the YMM registers
  // saved by the system (OSXSAVE, XCR0's SSE and AVX bits), the test libgcc makes. Elsewhere the
  // processor is asked once, here. A function-local static: no order among constructors matters.
#if SOFTTRACE_GLIBC_CPU_FEATURES
  static const bool usable = CPU_FEATURE_ACTIVE(AVX2);
#else
  static const bool usable = [] {
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (__get_cpuid_max(0, nullptr) < 7) return false;
    __cpuid(1, a, b, c, d);
    if (!(c & bit_OSXSAVE) || !(c & bit_AVX)) return false;
    unsigned xcr0 = 0, xcr0_high = 0;
    __asm__("xgetbv" : "=a"(xcr0), "=d"(xcr0_high) : "c"(0));
    if ((xcr0 & 6u) != 6u) return false;
    __cpuid_count(7, 0, a, b, c, d);
    return (b & bit_AVX2) != 0;
  }();
#endif
  return usable;
}

}  // namespace softtrace

// What the kernel says of transparent huge pages, for the tests of memory advised to use them
// (film/plane_memory.h, cli/heap_pages.h).
#pragma once

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

namespace softtrace::test {

// smaps' THPeligible of the mapping holding `p`, or -1 where the file has no such line.
inline int thp_eligible(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const uintptr_t a = reinterpret_cast<uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long lo = 0, hi = 0;
    char dash = 0;
    if (std::sscanf(line.c_str(), "%lx%c%lx", &lo, &dash, &hi) == 3 && dash == '-' &&
        line.find(':') > line.find(' ')) {
      inside = lo <= a && a < hi;
    } else if (inside && line.rfind("THPeligible:", 0) == 0) {
      return std::stoi(line.substr(12));
    }
  }
  return -1;
}

// Whether the kernel grants huge pages to memory advised so (its mode "always" or "madvise").
inline bool huge_pages_on_advice() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(f, modes);
  return modes.find("[always]") != std::string::npos ||
         modes.find("[madvise]") != std::string::npos;
}

}  // namespace softtrace::test

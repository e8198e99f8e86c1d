// Where softtrace-core lies: beside the program that runs, whatever its name or folder, so that a
// build tree and an installed prefix each run their own.
#pragma once

#include <cstddef>

namespace softtrace {

// Writes the path of softtrace-core in this program's folder (/proc/self/exe's) to `path`, null
// terminated; false where the folder cannot be read or the path does not fit in `size` bytes.
bool core_path(char* path, std::size_t size);

}  // namespace softtrace

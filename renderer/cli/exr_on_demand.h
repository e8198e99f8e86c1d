// The command line's EXR module (cli/exr_on_demand.cpp): softtrace-exr.so, opened at the first
// EXR read or written.
#pragma once

namespace softtrace {

// Opens the module now, as the first read_exr or write_exr would (once for the process), and
// throws what they would throw if it cannot: a render with an EXR output asks before its frame,
// so that a missing module fails the run before the work rather than after it.
void load_exr_module();

}  // namespace softtrace

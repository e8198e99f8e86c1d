// A command's results on standard output must reach it: `eval ... >/dev/full` once exited 0
// with nothing written.
#pragma once

namespace softtrace {

// Flushes stdout. When that or any earlier write to it failed, says so on stderr (one line) and
// returns `failure_status`; otherwise returns `status`.
int checked_standard_output(int status, int failure_status);

}  // namespace softtrace

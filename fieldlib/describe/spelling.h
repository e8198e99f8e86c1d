// Near misses for "did you mean ...?" messages: the scene loader's keys and the command line's
// words use the same distance.
#pragma once

#include <string>

namespace softtrace {

// Optimal-string-alignment distance: insertions, deletions, substitutions and swaps of two
// neighbouring characters each cost 1 ("rendr" and "rednre" are 1 and 2 from "render").
size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace softtrace

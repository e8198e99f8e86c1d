// Option checks whose refusals name the value and the rule in our words (CLI11's own ranges say
// "Value -1 not in range 0 to 1.797...e308" with all 309 digits, or let NaN through).
#pragma once

#include <CLI/CLI.hpp>

namespace softtrace {

// A finite number from 0 to 100 (NaN is refused: it once turned every mismatch into a pass).
CLI::Validator percentage_check();

// A whole number from `lo` to `hi`, written as digits (no exponent, no fraction).
CLI::Validator whole_number_check(long long lo, long long hi);

}  // namespace softtrace

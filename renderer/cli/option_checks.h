// The command line's checks of option values, in our words: each refusal names the value and the
// rule ("--width: expected an integer from 1 to 16384, got '0'"; CLI11 prefixes the option's
// name), where CLI11's own validators print their internals ("Check foo value in
// {global->1,local->0} OR {1,0} FAILED") or the largest double. A value is checked as text,
// before CLI11 converts it, so no conversion error can follow a passed check.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "trace/tracer.h"

namespace softtrace {

// A decimal integer (no exponent, no fraction) in [lo, hi].
CLI::Validator integer_in(long long lo, long long hi);
// A decimal integer >= lo, any size that fits a long long.
CLI::Validator integer_at_least(long long lo);
// A finite number in [lo, hi].
CLI::Validator number_in(double lo, double hi);
// A number >= 0, "inf" included (idiff's thresholds; -hardfail's default is infinite).
CLI::Validator threshold_value();
// A comma-separated subset of depth, normal, steps (film.h parse_aovs).
CLI::Validator aov_list();
// A finite number > 0.
CLI::Validator number_above_zero();
// A finite number.
CLI::Validator finite_number();
// "X,Y,Z": three finite numbers, comma-separated.
CLI::Validator point_xyz();
// The point of a text point_xyz() passed.
Vec3 point_of(const std::string& text);
// "local" or "global", any case, turned into the LipschitzMode's number for CLI11 to store.
CLI::Validator lipschitz_mode();

// The message of a CLI11 parse error in our words (without the "softtrace: " prefix): a value
// missing after an option, an option given twice, a value given to a flag, arguments nobody
// expects, no subcommand.
std::string usage_error_text(const CLI::ParseError& error);

}  // namespace softtrace

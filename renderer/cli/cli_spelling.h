// Misspelled subcommands and options: CLI11 says only that an argument "was not expected"; this
// names the unknown word and the known one nearest to it.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "describe/spelling.h"

namespace softtrace {

// The name nearest to `word` within an edit distance of 2 and below its number of letters (the
// first of equals), or "".
std::string nearest_name(const std::string& word, const std::vector<std::string>& names);

// The first subcommand or option on the command line that `app` does not know, as
// "unknown command 'rendr' (did you mean 'render'?)"; "" when every word is known.
std::string unknown_word(const CLI::App& app, int argc, const char* const* argv);

}  // namespace softtrace

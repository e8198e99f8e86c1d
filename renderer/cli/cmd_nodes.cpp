// `softtrace nodes`: the one list of kinds (fieldlib/kinds.h), for people or for the fuzzer.
#include <cstdio>

#include "cli/commands.h"
#include "loader/kinds.h"

namespace softtrace {

int run_nodes(bool dict) {
  const std::string text = dict ? fuzz_dictionary() : describe_kinds();
  std::fputs(text.c_str(), stdout);
  return 0;
}

}  // namespace softtrace

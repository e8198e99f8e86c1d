#include "cli/option_checks.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace softtrace {

CLI::Validator percentage_check() {
  return CLI::Validator(
      [](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        return end != text.c_str() && *end == '\0' && v >= 0 && v <= 100
                   ? std::string()
                   : "'" + text + "' is not a percentage from 0 to 100";
      },
      "0..100");
}

CLI::Validator whole_number_check(long long lo, long long hi) {
  const std::string rule =
      "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, rule](std::string& text) {
        const size_t digits = text.find_first_not_of("0123456789", text[0] == '-' ? 1 : 0);
        const bool whole = digits == std::string::npos && text.size() > (text[0] == '-' ? 1u : 0u);
        errno = 0;
        const long long v = whole ? std::strtoll(text.c_str(), nullptr, 10) : 0;
        return whole && errno == 0 && v >= lo && v <= hi ? std::string()
                                                         : "'" + text + "' is not " + rule;
      },
      std::to_string(lo) + ".." + std::to_string(hi));
}

}  // namespace softtrace

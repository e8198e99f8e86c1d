#include "cli/option_checks.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "film/film.h"

namespace softtrace {

namespace {

// Whether `text` is a whole decimal integer that fits a long long.
bool parse_integer(const std::string& text, long long& value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return errno == 0 && end != text.c_str() && *end == '\0';
}

// Whether `text` is a whole number (decimal or with an exponent), finite or, when allowed,
// "inf"; never NaN.
bool parse_number(const std::string& text, double& value, bool allow_infinity = false) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' &&
         (std::isfinite(value) || (allow_infinity && std::isinf(value)));
}

std::string got(const std::string& text) {
  return ", got '" + text + "'";
}

// "1e-06" -> "1e-06", 100 -> "100": the bound as a person writes it.
std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

}  // namespace

CLI::Validator integer_in(long long lo, long long hi) {
  const std::string rule =
      "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, rule](std::string& text) {
        long long v = 0;
        return parse_integer(text, v) && v >= lo && v <= hi ? std::string() : rule + got(text);
      },
      "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

CLI::Validator integer_at_least(long long lo) {
  const std::string rule = "expected an integer >= " + std::to_string(lo);
  return CLI::Validator(
      [lo, rule](std::string& text) {
        long long v = 0;
        return parse_integer(text, v) && v >= lo ? std::string() : rule + got(text);
      },
      ">= " + std::to_string(lo));
}

CLI::Validator number_in(double lo, double hi) {
  const std::string rule = "expected a number from " + number_text(lo) + " to " + number_text(hi);
  return CLI::Validator(
      [lo, hi, rule](std::string& text) {
        double v = 0;
        return parse_number(text, v) && v >= lo && v <= hi ? std::string() : rule + got(text);
      },
      "[" + number_text(lo) + ", " + number_text(hi) + "]");
}

namespace {

bool parse_point(const std::string& text, Vec3& p) {
  size_t begin = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t end = i < 2 ? text.find(',', begin) : text.size();
    if (end == std::string::npos || !parse_number(text.substr(begin, end - begin), p[i]))
      return false;
    begin = end + 1;
  }
  return true;
}

}  // namespace

CLI::Validator point_xyz() {
  return CLI::Validator(
      [](std::string& text) {
        Vec3 p;
        return parse_point(text, p) ? std::string()
                                    : "expected X,Y,Z (three finite numbers)" + got(text);
      },
      "X,Y,Z");
}

Vec3 point_of(const std::string& text) {
  Vec3 p;
  parse_point(text, p);
  return p;
}

CLI::Validator threshold_value() {
  return CLI::Validator(
      [](std::string& text) {
        double v = 0;
        return parse_number(text, v, true) && v >= 0 ? std::string()
                                                     : "expected a number >= 0" + got(text);
      },
      ">= 0");
}

CLI::Validator aov_list() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parse_aovs(text);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      "depth,normal,steps,albedo");
}

CLI::Validator number_above_zero() {
  return CLI::Validator(
      [](std::string& text) {
        double v = 0;
        return parse_number(text, v) && v > 0 ? std::string()
                                              : "expected a finite number > 0" + got(text);
      },
      "> 0");
}

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) {
        double v = 0;
        return parse_number(text, v) ? std::string() : "expected a finite number" + got(text);
      },
      "finite");
}

CLI::Validator lipschitz_mode() {
  return CLI::Validator(
      [](std::string& text) {
        std::string lower = text;
        for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (lower == "local") {
          text = std::to_string(static_cast<int>(LipschitzMode::Local));
        } else if (lower == "global") {
          text = std::to_string(static_cast<int>(LipschitzMode::Global));
        } else {
          return "expected local or global" + got(text);
        }
        return std::string();
      },
      "local|global");
}

std::string usage_error_text(const CLI::ParseError& error) {
  const std::string what = error.what();
  const auto after = [&](const std::string& prefix) { return what.substr(prefix.size()); };
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
    // "NAME: 1 required TYPE missing" or "NAME: At Most 1 required but received N".
    const std::string name = what.substr(0, what.find(':'));
    if (what.find(" missing") != std::string::npos) return name + ": expected a value after it";
    if (what.find("At Most") != std::string::npos) return name + ": given more than once";
    const std::string override = " was given a disallowed flag override";
    if (what.size() > override.size() &&
        what.compare(what.size() - override.size(), override.size(), override) == 0) {
      const std::string flag = what.substr(0, what.size() - override.size());  // CLI11: "quiet"
      return (flag[0] == '-' ? "" : "--") + flag + ": a flag takes no value";
    }
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) {
    const std::string one = "The following argument was not expected: ";
    const std::string more = "The following arguments were not expected: ";
    if (what.rfind(one, 0) == 0) return "unexpected argument '" + after(one) + "'";
    if (what.rfind(more, 0) == 0) return "unexpected arguments: " + after(more);
  }
  if (what == "A subcommand is required")
    return "expected a command: render, eval, mesh, diff, bench, merge or nodes";
  return what;
}

}  // namespace softtrace

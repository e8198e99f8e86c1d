#include "describe/kind_info.h"

#include <cmath>
#include <sstream>

namespace softtrace {

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

const char* family_phrase(Family f) {
  switch (f) {
    case Family::Distance:
      return "a distance function";
    case Family::SoftField:
      return "a soft field";
    case Family::ZeroSurface:
      return "a zero-surface function";
    case Family::Constructive:
      return "a constructive field";
    case Family::ConventionField:
      return "a field of the object's convention";
    case Family::Any:
      return "any node";
    case Family::Potential:
      return "a potential";
    case Family::RadiusTransform:
      return "a radius transform";
  }
  return "";
}

Family convention_family(Convention c) {
  switch (c) {
    case Convention::Soft:
      return Family::SoftField;
    case Convention::Zero:
      return Family::ZeroSurface;
    case Convention::Constructive:
      return Family::Constructive;
  }
  return Family::SoftField;
}

Family resolve(Family f, Convention c) {
  return f == Family::ConventionField ? convention_family(c) : f;
}

bool fits(Family wanted, Family given) {
  return wanted == Family::Any || wanted == given ||
         (wanted == Family::Constructive && given == Family::Distance);
}

std::string range_text(const ParamSpec& p) {
  const bool lo = std::isfinite(p.lo), hi = std::isfinite(p.hi);
  if (lo && hi)
    return std::string(p.lo_closed ? "[" : "(") + number_text(p.lo) + ", " + number_text(p.hi) +
           (p.hi_closed ? "]" : ")");
  if (lo) return (p.lo_closed ? ">= " : "> ") + number_text(p.lo);
  if (hi) return (p.hi_closed ? "<= " : "< ") + number_text(p.hi);
  return "";
}

std::string type_text(const ParamSpec& p) {
  switch (p.type) {
    case ParamType::Number:
      return "number";
    case ParamType::Integer:
      return "integer";
    case ParamType::Choice: {
      std::string s, c = p.choices;
      for (size_t at = 0; at <= c.size();) {
        const size_t bar = std::min(c.find('|', at), c.size());
        s += (s.empty() ? "\"" : " or \"") + c.substr(at, bar - at) + "\"";
        at = bar + 1;
      }
      return s;
    }
    case ParamType::Vec3:
      return "[x, y, z]";
    case ParamType::Numbers:
      return p.min_count ? std::to_string(p.min_count) + " numbers" : "list of numbers";
    case ParamType::NumberOrList:
      return "number or list";
    case ParamType::Vec3List:
      return "list of [x, y, z]";
    case ParamType::Node:
      return std::string(family_phrase(p.slot)).substr(2) + " node";
    case ParamType::Nodes: {
      std::string n = p.min_count == p.max_count ? std::to_string(p.min_count)
                      : p.max_count
                          ? std::to_string(p.min_count) + " to " + std::to_string(p.max_count)
                          : std::to_string(p.min_count) + " or more";
      return n + " × " + std::string(family_phrase(p.slot)).substr(2);
    }
    case ParamType::Potential:
      return "potential";
    case ParamType::RadiusTransform:
      return "radius transform";
    case ParamType::Object:
      return "object";
  }
  return "";
}

std::string default_text(const ParamSpec& p) {
  switch (p.need) {
    case Need::Required:
      return "required";
    case Need::Optional:
      return p.fallback;
    case Need::Conditional:
      return std::string("required with ") + p.fallback;
  }
  return "";
}

}  // namespace softtrace

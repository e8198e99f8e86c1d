// The checks every kind's parameters get from the table (kinds.h), before its `create` runs.
#include <cmath>

#include "describe/building.h"
#include "loader/placement_keys.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

std::string choices_text(const std::string& c) {
  std::vector<std::string> names;
  for (size_t at = 0; at <= c.size();) {
    const size_t bar = std::min(c.find('|', at), c.size());
    names.push_back("\"" + c.substr(at, bar - at) + "\"");
    at = bar + 1;
  }
  std::string s;
  for (size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return s;
}

bool is_choice(const std::string& c, const std::string& v) {
  for (size_t at = 0; at <= c.size();) {
    const size_t bar = std::min(c.find('|', at), c.size());
    if (c.compare(at, bar - at, v) == 0 && v.size() == bar - at) return true;
    at = bar + 1;
  }
  return false;
}

// What is wrong with the number `v` for `spec`, or "" when it is in range. The message is built
// only for a number that is wrong: formatting the range for every number read was 15% of loading
// a 1000-blob scene.
std::string number_problem(const ParamSpec& spec, const json& v) {
  if (!v.is_number()) return "expected a number, got " + json_excerpt(v);
  const double x = v.get<double>();
  const bool in = (x > spec.lo || (spec.lo_closed && x == spec.lo)) &&
                  (x < spec.hi || (spec.hi_closed && x == spec.hi));
  const bool interval = std::isfinite(spec.lo) && std::isfinite(spec.hi);
  if (!in)
    return "expected " + std::string(spec.noun) + (interval ? " in " : " ") + range_text(spec) +
           ", got " + json_excerpt(v);
  if (std::abs(x) > kMaxMagnitude)
    return "expected a number of magnitude at most 1e150 (docs/scene-format.md), got " +
           json_excerpt(v);
  if (spec.lo == 0 && !spec.lo_closed && x < kMinPositive)
    return "expected " + std::string(spec.noun) +
           " of at least 1e-150 (docs/scene-format.md), got " + json_excerpt(v);
  return "";
}

void check_number(const Params& p, const ParamSpec& spec, const json& v) {
  const std::string problem = number_problem(spec, v);
  if (!problem.empty()) p.fail(spec.name, problem);
}

// A non-empty array of numbers, each checked; `count` elements when non-zero.
void check_numbers(const Params& p, const ParamSpec& spec, const json& v, size_t count) {
  if (!v.is_array() || v.empty())
    p.fail(spec.name, "expected a non-empty array of numbers, got " + json_excerpt(v));
  if (count && v.size() != count)
    p.fail(spec.name, "expected " + std::to_string(count) + " numbers, got " + json_excerpt(v));
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string problem = number_problem(spec, v[i]);
    if (!problem.empty()) p.fail_at(spec.name, std::to_string(i), problem);
  }
}

void check_vec3(const Params& p, const ParamSpec& spec, const json& v, const std::string& at) {
  const std::string key = at.empty() ? spec.name : std::string(spec.name) + "/" + at;
  if (!v.is_array() || v.size() != 3) p.fail(key, "expected [x, y, z], got " + json_excerpt(v));
  for (size_t i = 0; i < 3; ++i) {
    const std::string problem = number_problem(spec, v[i]);
    if (!problem.empty()) p.fail(key + "/" + std::to_string(i), problem);
  }
}

void check_value(const Params& p, const ParamSpec& spec, const json& v) {
  switch (spec.type) {
    case ParamType::Number:
      return check_number(p, spec, v);
    case ParamType::Integer:
      if (!v.is_number_integer() || v.get<double>() < spec.lo || v.get<double>() > spec.hi)
        p.fail(spec.name, "expected an integer in [" + std::to_string(int(spec.lo)) + ", " +
                              std::to_string(int(spec.hi)) + "], got " + json_excerpt(v));
      return;
    case ParamType::Choice:
      if (!v.is_string() || !is_choice(spec.choices, v.get<std::string>()))
        p.fail(spec.name, "expected " + choices_text(spec.choices) + ", got " +
                              (v.is_string() ? "'" + v.get<std::string>() + "'" : json_excerpt(v)));
      return;
    case ParamType::Vec3:
      return check_vec3(p, spec, v, "");
    case ParamType::Numbers:
      return check_numbers(p, spec, v, spec.min_count);
    case ParamType::NumberOrList:
      return v.is_number() ? check_number(p, spec, v) : check_numbers(p, spec, v, 0);
    case ParamType::Vec3List:
      if (!v.is_array() || v.empty())
        p.fail(spec.name, "expected a non-empty array of [x, y, z], got " + json_excerpt(v));
      for (size_t i = 0; i < v.size(); ++i) check_vec3(p, spec, v[i], std::to_string(i));
      return;
    case ParamType::Nodes: {
      if (!v.is_array()) p.fail(spec.name, "expected an array, got " + json_excerpt(v));
      const size_t n = v.size(), lo = spec.min_count;
      const size_t hi = spec.max_count ? spec.max_count : kMaxChildren;
      if (lo == hi && n != lo)
        p.fail(spec.name, "expected exactly " + std::to_string(lo) +
                              (lo == 1 ? " child, got " : " children, got ") + std::to_string(n));
      if (n < lo)
        p.fail(spec.name, "expected at least " + std::to_string(lo) +
                              (lo == 1 ? " child, got " : " children, got ") + std::to_string(n));
      if (n > hi)
        p.fail(spec.name,
               "expected at most " + std::to_string(hi) + " children, got " + std::to_string(n));
      return;
    }
    case ParamType::Node:
    case ParamType::Potential:
    case ParamType::RadiusTransform:
    case ParamType::Object:
      if (!v.is_object()) p.fail(spec.name, "expected an object, got " + json_excerpt(v));
      return;
  }
}

}  // namespace

void check_params(const KindInfo& kind, const Params& p, bool placement) {
  const json& j = p.raw();
  // Each spec's value, found by the pass over the keys that checks them: a search of the
  // object's map per spec compared every spec's name with the keys again.
  constexpr size_t kMaxSpecs = 64;
  const size_t specs = kind.params.size();
  const bool noted = specs <= kMaxSpecs;
  const json* value[kMaxSpecs] = {};
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    bool ok = same_name(key, "type");
    ok = ok || (placement && is_placement_key(key));
    for (size_t i = 0; i < specs; ++i)
      if (same_name(key, kind.params[i].name)) {
        ok = true;
        if (noted) value[i] = &*it;
      }
    if (ok) continue;
    // The list is built only for the message: every node of a scene passes here.
    std::vector<std::string> known = {"type"};
    if (placement) known.insert(known.end(), std::begin(kPlacementKeys), std::end(kPlacementKeys));
    for (const auto& spec : kind.params) known.push_back(spec.name);
    p.fail(json_pointer_escape(key), unknown_key_message(key, known));
  }
  for (size_t i = 0; i < specs; ++i) {
    const ParamSpec& spec = kind.params[i];
    const json* v = noted ? value[i] : nullptr;
    if (!noted) {
      const auto at = j.find(spec.name);
      v = at != j.end() ? &*at : nullptr;
    }
    if (v)
      check_value(p, spec, *v);
    else if (spec.need == Need::Required)
      p.fail(spec.name, "missing required parameter '" + std::string(spec.name) + "'");
  }
}

}  // namespace softtrace

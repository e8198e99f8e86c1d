// Every node type a piece of scene JSON names, for tests that compare the kinds in use with the
// table and the documentation.
#pragma once

#include <nlohmann/json.hpp>
#include <set>
#include <string>

namespace softtrace::test {

// Every "type" value anywhere in `j`.
inline void collect_types(const nlohmann::json& j, std::set<std::string>& out) {
  if (j.is_object()) {
    if (j.contains("type") && j.at("type").is_string()) out.insert(j.at("type").get<std::string>());
    for (const auto& v : j) collect_types(v, out);
  } else if (j.is_array()) {
    for (const auto& v : j) collect_types(v, out);
  }
}

}  // namespace softtrace::test

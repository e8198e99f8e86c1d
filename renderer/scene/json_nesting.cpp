#include "scene/json_nesting.h"

#include "describe/params.h"
#include "scene/json_location.h"

namespace softtrace {

void check_json_nesting(const std::string& text, const std::string& name) {
  int depth = 0;
  scan_json(text, [&](size_t i) {
    const char c = text[i];
    if ((c == '[' || c == '{') && ++depth > kMaxJsonNesting)
      throw SceneError(name + ":" + line_col(text, i) + ": nesting deeper than " +
                       std::to_string(kMaxJsonNesting) + " levels");
    if (c == ']' || c == '}') --depth;
    return true;
  });
}

}  // namespace softtrace

#include "scene/json_location.h"

namespace softtrace {

std::string line_col(const std::string& text, size_t offset) {
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    const bool cr_alone = text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n');
    if (text[i] == '\n' || cr_alone) {
      ++line;
      line_start = i + 1;
    }
  }
  return std::to_string(line) + ":" + std::to_string(offset - line_start + 1);
}

size_t object_key_offset(const std::string& text, size_t index) {
  size_t found = std::string::npos, keys = 0;
  size_t last_string = std::string::npos;  // the string just before, if nothing else came after
  scan_json(text, [&](size_t i) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') return true;
    if (c == ':' && last_string != std::string::npos && keys++ == index) {
      found = last_string;
      return false;
    }
    last_string = c == '"' ? i : std::string::npos;
    return true;
  });
  return found;
}

}  // namespace softtrace

#include "json_nesting.h"

#include "params.h"

namespace softtrace {

void check_json_nesting(const std::string& text, const std::string& name) {
  int depth = 0;
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    } else if (c == '"') {  // skip the string; an unterminated one is the parser's to report
      for (++i; i < text.size() && text[i] != '"' && text[i] != '\n'; ++i)
        if (text[i] == '\\') ++i;
      if (i < text.size() && text[i] == '\n') --i;  // let the loop count the line
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      for (i += 2; i + 1 < text.size() && !(text[i] == '*' && text[i + 1] == '/'); ++i)
        if (text[i] == '\n') {
          ++line;
          line_start = i + 1;
        }
      ++i;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        throw SceneError(name + ":" + std::to_string(line) + ":" +
                         std::to_string(i - line_start + 1) + ": nesting deeper than " +
                         std::to_string(kMaxJsonNesting) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

}  // namespace softtrace

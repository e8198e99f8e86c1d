// Where things are in scene text, for error messages: "LINE:COL" of a byte and the offset of the
// n-th object key. The parser validates the text; these only need to find their way through
// strings and // and /* */ comments the way it does.
#pragma once

#include <cstddef>
#include <string>

namespace softtrace {

// "LINE:COL" (both from 1, the column in bytes) of the byte at `offset`. "\n", "\r\n" and a lone
// "\r" (old Mac files) each end a line. An offset past the end names the position after the
// last byte.
std::string line_col(const std::string& text, size_t offset);

// Calls visit(offset) for every byte outside strings and comments and for the opening quote of
// every string, in order, until it returns false. A string ends at its closing quote or, if it
// is unterminated, before the line break (the parser reports it).
template <class Visit>
void scan_json(const std::string& text, Visit visit) {
  const size_t n = text.size();
  for (size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      // As the parser: a line break, or a NUL (which it takes as part of the comment), ends it.
      while (i + 1 < n && text[i + 1] != '\n' && text[i + 1] != '\r' && text[i + 1] != '\0') ++i;
      if (i + 1 < n && text[i + 1] == '\0') ++i;
      continue;
    }
    if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      for (i += 2; i + 1 < n && !(text[i] == '*' && text[i + 1] == '/'); ++i) {
      }
      ++i;
      continue;
    }
    if (!visit(i)) return;
    if (c == '"') {
      for (++i; i < n && text[i] != '"' && text[i] != '\n' && text[i] != '\r'; ++i)
        if (text[i] == '\\') ++i;
      if (i < n && text[i] != '"') --i;  // the line break is not part of the string
    }
  }
}

// The offset of the opening quote of the `index`-th (from 0) object key in document order, or
// std::string::npos if there are fewer keys.
size_t object_key_offset(const std::string& text, size_t index);

}  // namespace softtrace

// A pre-check of scene text before parsing: the parser itself is iterative, but everything that
// walks the parsed document afterwards (building fields, printing a value in an error, freeing
// it) recurses, so a hostile file of 100,000 nested brackets must be refused up front.
#pragma once

#include <string>

namespace softtrace {

constexpr int kMaxJsonNesting = 1000;

// Throws SceneError "name:line:col: nesting deeper than ..." at the first bracket that opens
// level kMaxJsonNesting + 1. Understands strings (with escapes) and // and /* */ comments; other
// syntax errors are left to the parser.
void check_json_nesting(const std::string& text, const std::string& name);

}  // namespace softtrace

// Scene text to a JSON document without keeping track of where anything is: the common case of
// a well-formed file, about twenty times fewer instructions than the located parser
// (json_text.h), whose lexer copies every byte into a token buffer and counts lines, and whose
// key check hashes every key. A file of 1000 blobs spent a third of its load there.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace softtrace {

// Parses `text` (strict JSON with // and /* */ comments, as the located parser reads it) into
// `out` and returns true, or returns false without a word for anything it does not take exactly
// as the located parser would: every error (syntax, a repeated key, nesting deeper than
// kMaxJsonNesting, a number beyond the double range) and also what it leaves to that parser
// although valid (escapes and non-ASCII bytes in strings, integers beyond 64 bits, numbers
// below the double range, a byte order mark, NUL bytes). The caller then runs the located
// parser, which gives the same document or the one located error. Where it returns true, `out`
// equals that parser's document value for value and type for type (unsigned for integers
// without a sign, as nlohmann's own parser types them).
bool parse_json_fast(const std::string& text, nlohmann::json& out);

}  // namespace softtrace

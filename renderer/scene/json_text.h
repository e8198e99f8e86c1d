// Scene text to a JSON document (JSON with // and /* */ comments), refusing with one located
// error what the document could not represent faithfully.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace softtrace {

// Throws SceneError "name:LINE:COL: ..." for nesting deeper than kMaxJsonNesting, a syntax error,
// a number beyond the double range, and a key repeated in one object (also when spelled with
// escapes, "f\u006fv" after "fov"): nlohmann would silently keep the last value. A well-formed
// file takes json_fast.h's parser; anything else this one's located parser, below.
nlohmann::json parse_json_text(const std::string& text, const std::string& name);

// The located parser alone: the same document or the same error, at several times the cost.
nlohmann::json parse_json_located(const std::string& text, const std::string& name);

// Empties `doc` from its leaves up. nlohmann's destructor moves the children of every array and
// object to a stack on the heap before freeing them (no recursion, for documents of any depth):
// a fifth of a 1000-component scene's load went to it. Documents from the parsers above are at
// most kMaxJsonNesting deep, so this recursion is bounded, and every container is empty by the
// time its own destructor runs, which then moves nothing.
void release_json(nlohmann::json& doc);

}  // namespace softtrace

#include "scene/json_text.h"

#include <unordered_set>
#include <vector>

#include "describe/params.h"
#include "scene/json_fast.h"
#include "scene/json_location.h"
#include "scene/json_nesting.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

// nlohmann's DOM builder, keeping where a syntax error, an out-of-range number or a duplicate
// key is: its own exception for "1e400" carries no position, its line numbers count only "\n",
// and it keeps the last of duplicate keys without a word.
class LocatingParser : public nlohmann::detail::json_sax_dom_parser<json> {
 public:
  LocatingParser(json& root, const std::string& text)
      : json_sax_dom_parser(root, false), text_(text) {}

  bool start_object(std::size_t size) {
    keys_.emplace_back();
    return json_sax_dom_parser::start_object(size);
  }

  bool end_object() {
    keys_.pop_back();
    return json_sax_dom_parser::end_object();
  }

  // `name` is decoded, so escapes cannot hide a duplicate. SAX events carry no position; the
  // key's place is found by counting keys in the text.
  bool key(std::string& name) {
    if (!keys_.back().insert(name).second) {
      where = line_col(text_, object_key_offset(text_, keys_seen_));
      const std::string quoted = json(name).dump(-1, ' ', false, json::error_handler_t::replace);
      message = "duplicate key '" + quoted.substr(1, quoted.size() - 2) + "'";  // escaped
      return false;
    }
    ++keys_seen_;
    return json_sax_dom_parser::key(name);
  }

  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& ex) {
    const std::string what = ex.what();
    if (ex.id == 406) {  // a number token: no escapes, so its length locates its start
      where = line_col(text_, position >= token.size() ? position - token.size() : 0);
      message = "invalid JSON: number out of range: " + token;
    } else {  // `position` counts the offending byte (or the end of input) as read
      where = line_col(text_, position > 0 ? position - 1 : 0);
      const size_t at = what.find("at line ");
      message = "invalid JSON: " +
                (at == std::string::npos ? what : what.substr(what.find(": ", at) + 2));
    }
    return false;
  }

  std::string where, message;  // empty where: no error

 private:
  const std::string& text_;
  std::vector<std::unordered_set<std::string>> keys_;  // per open object
  size_t keys_seen_ = 0;
};

}  // namespace

json parse_json_text(const std::string& text, const std::string& name) {
  json doc;
  if (parse_json_fast(text, doc)) return doc;
  return parse_json_located(text, name);
}

json parse_json_located(const std::string& text, const std::string& name) {
  check_json_nesting(text, name);
  json doc;
  LocatingParser parser(doc, text);
  json::sax_parse(text, &parser, nlohmann::detail::input_format_t::json, true,
                  /*ignore_comments=*/true);
  if (!parser.where.empty()) throw SceneError(name + ":" + parser.where + ": " + parser.message);
  return doc;
}

void release_json(nlohmann::json& doc) {
  if (doc.is_object()) {
    auto& members = doc.get_ref<nlohmann::json::object_t&>();
    for (auto& member : members) release_json(member.second);
    members.clear();
  } else if (doc.is_array()) {
    auto& items = doc.get_ref<nlohmann::json::array_t&>();
    for (auto& item : items) release_json(item);
    items.clear();
  }
}

}  // namespace softtrace

#include "describe/params.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "describe/spelling.h"

namespace softtrace {

namespace {
std::string describe(const nlohmann::json& v) {
  std::string s = v.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

// The finite number array[i] of the array `key` of `p`, or the located error.
double element(const Params& p, const std::string& key, const nlohmann::json& array, size_t i) {
  const nlohmann::json& e = array[i];
  if (!e.is_number()) p.fail_at(key, std::to_string(i), "expected a number, got " + describe(e));
  const double d = e.get<double>();
  if (!std::isfinite(d))
    p.fail_at(key, std::to_string(i), "expected a finite number, got " + describe(e));
  return d;
}

}  // namespace

std::string json_excerpt(const nlohmann::json& v) {
  return describe(v);
}

std::string unknown_key_message(const std::string& key, const std::vector<std::string>& known) {
  std::string best;
  size_t best_d = 3;
  // Keys longer than 64 characters are no one's typo; skip the quadratic table for them.
  if (key.size() <= 64)
    for (const auto& k : known) {
      // Case differences cost nothing; a key as short as the edits needed is no near miss.
      std::string a = key, b = k;
      for (auto& c : a) c = char(std::tolower(static_cast<unsigned char>(c)));
      for (auto& c : b) c = char(std::tolower(static_cast<unsigned char>(c)));
      const size_t d = edit_distance(a, b);
      if (k != key && d < best_d && d < std::max(a.size(), b.size())) best = k, best_d = d;
    }
  std::string m = "unknown key '" + key + "'";
  if (!best.empty()) m += " (did you mean '" + best + "'?)";
  return m;
}

std::string printable(const std::string& text) {
  const auto control = [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; };
  if (std::none_of(text.begin(), text.end(), control)) return text;  // every message we write
  std::string out;
  for (char c : text) {
    if (!control(c)) {
      out += c;
      continue;
    }
    char escape[7];
    std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned char>(c));
    out += escape;
  }
  return out;
}

namespace {

// `key` escaped for a JSON pointer ('~' as "~0", '/' as "~1"), appended to `out`.
void append_escaped(std::string& out, const std::string& key) {
  if (std::none_of(key.begin(), key.end(), [](char c) { return c == '~' || c == '/'; })) {
    out += key;  // every key the loader names
    return;
  }
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
}

}  // namespace

std::string json_pointer_escape(const std::string& key) {
  std::string out;
  append_escaped(out, key);
  return out;
}

Params::Params(const json& j, std::string pointer, std::shared_ptr<const std::string> file)
    : j_(&j), pointer_(std::move(pointer)), file_(std::move(file)) {
  if (!j.is_object()) fail("", "expected an object, got " + describe(j));
}

std::string Params::where(const std::string& key) const {
  std::string p = key.empty() ? pointer_ : pointer_ + "/" + key;
  if (p.empty()) p = "/";
  return *file_ + ": " + p;
}

void Params::fail(const std::string& key, const std::string& what) const {
  throw SceneError(where(key) + ": " + what);
}

void Params::fail_at(const std::string& key, const std::string& index_path,
                     const std::string& what) const {
  throw SceneError(where(key) + "/" + index_path + ": " + what);
}

void Params::check_keys(const std::vector<std::string>& known, const std::string& context) const {
  for (auto it = j_->begin(); it != j_->end(); ++it)
    if (std::find(known.begin(), known.end(), it.key()) == known.end())
      fail(json_pointer_escape(it.key()), unknown_key_message(it.key(), known) + context);
  known_ = known;
}

namespace {

// The member `key` of `j` (null when j is no object or lacks it). A node has a handful of keys:
// comparing lengths first and walking them in order beats the map's descent, whose every step
// compares two strings (a fifth of the lookups' cost in a 1000-blob scene).
const nlohmann::json* member(const nlohmann::json& j, const std::string& key) {
  if (!j.is_object()) return nullptr;
  const auto& members = j.get_ref<const nlohmann::json::object_t&>();
  constexpr size_t kScanned = 8;
  if (members.size() > kScanned) {
    const auto it = members.find(key);
    return it == members.end() ? nullptr : &it->second;
  }
  for (const auto& m : members)
    if (m.first.size() == key.size() && m.first.compare(key) == 0) return &m.second;
  return nullptr;
}

}  // namespace

const nlohmann::json* Params::lookup(const std::string& key) const {
  if (!known_.empty() && std::find(known_.begin(), known_.end(), key) == known_.end())
    throw std::logic_error("the loader reads '" + key + "' at " + where("") +
                           ", which its list of keys does not have");
  const json* v = member(*j_, key);
  if (!v) {
    // An object has a handful of keys: a vector searched from the front beats a set.
    if (std::find(absent_.begin(), absent_.end(), key) == absent_.end()) {
      // One allocation for the handful: a node asks for its placement keys and optional
      // parameters, and a growth from four to eight moved them all (10% of the lookups).
      if (absent_.empty()) absent_.reserve(8);
      absent_.push_back(key);
    }
    return nullptr;
  }
  for (const Asked& a : asked_)
    if (a.value == v) return v;
  if (asked_.empty()) asked_.reserve(8);
  asked_.push_back({v, false});
  return v;
}

bool Params::has(const std::string& key) const {
  return lookup(key) != nullptr;
}

const nlohmann::json& Params::at(const std::string& key) const {
  const json* v = lookup(key);
  if (!v) fail(key, "missing required parameter '" + key + "'");
  for (Asked& a : asked_)
    if (a.value == v) a.read = true;
  return *v;
}

double Params::number(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_number()) fail(key, "expected a number, got " + describe(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "expected a finite number, got " + describe(v));
  return d;
}
double Params::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}
double Params::positive(const std::string& key) const {
  const double d = number(key);
  check(d > 0, key, "expected a number > 0, got " + describe(j_->at(key)));
  return d;
}
double Params::positive(const std::string& key, double fallback) const {
  return has(key) ? positive(key) : fallback;
}

int Params::integer(const std::string& key, int lo, int hi) const {
  const json& v = at(key);
  std::ostringstream range;
  range << "expected an integer in [" << lo << ", " << hi << "], got " << describe(v);
  if (!v.is_number_integer()) fail(key, range.str());
  const auto i = v.get<long long>();
  if (i < lo || i > hi) fail(key, range.str());
  return static_cast<int>(i);
}
int Params::integer(const std::string& key, int lo, int hi, int fallback) const {
  return has(key) ? integer(key, lo, hi) : fallback;
}

bool Params::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const json& v = at(key);
  if (!v.is_boolean()) fail(key, "expected true or false, got " + describe(v));
  return v.get<bool>();
}

std::string Params::string(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_string()) fail(key, "expected a string, got " + describe(v));
  return v.get<std::string>();
}
std::string Params::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

std::vector<double> Params::numbers(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array() || v.empty()) fail(key, "expected a non-empty array of numbers");
  std::vector<double> out;
  out.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) out.push_back(element(*this, key, v, i));
  return out;
}

std::vector<double> Params::numbers_or_scalar(const std::string& key, size_t count) const {
  if (has(key) && j_->at(key).is_number()) return std::vector<double>(count, number(key));
  std::vector<double> v = numbers(key);
  if (v.size() != count)
    fail(key, "expected a number or " + std::to_string(count) + " numbers, got " +
                  std::to_string(v.size()));
  return v;
}

Vec3 Params::vec3(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array() || v.size() != 3) fail(key, "expected [x, y, z], got " + describe(v));
  return {element(*this, key, v, 0), element(*this, key, v, 1), element(*this, key, v, 2)};
}
Vec3 Params::vec3(const std::string& key, const Vec3& fallback) const {
  return has(key) ? vec3(key) : fallback;
}

std::vector<Vec3> Params::vec3s(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array() || v.empty()) fail(key, "expected a non-empty array of [x, y, z]");
  std::vector<Vec3> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string sub = std::to_string(i);
    if (!v[i].is_array() || v[i].size() != 3)
      fail_at(key, sub, "expected [x, y, z], got " + describe(v[i]));
    Vec3 e;
    for (int c = 0; c < 3; ++c) {
      const json& x = v[i][c];
      if (!x.is_number() || !std::isfinite(x.get<double>()))
        fail_at(key, sub + "/" + std::to_string(c), "expected a finite number, got " + describe(x));
      e[c] = x.get<double>();
    }
    out.push_back(e);
  }
  return out;
}

Params Params::object(const std::string& key) const {
  const json& v = at(key);
  // One allocation: a component's pointer is longer than a short string, and the key is escaped
  // in place (an escape doubles a character at most) where a copy of it was made first.
  std::string pointer;
  pointer.reserve(pointer_.size() + 1 + 2 * key.size());
  pointer.append(pointer_).append(1, '/');
  append_escaped(pointer, key);
  return Params(v, std::move(pointer), file_);
}

std::vector<Params> Params::objects(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array()) fail(key, "expected an array, got " + describe(v));
  std::vector<Params> out;
  out.reserve(v.size());
  const std::string base = pointer_ + "/" + json_pointer_escape(key) + "/";
  // Each element's pointer in one allocation: `base + std::to_string(i)` made the index's string
  // and then a second, larger one for the pointer (a blend's 1000 children).
  char index[24];
  for (size_t i = 0; i < v.size(); ++i) {
    char* end = std::to_chars(index, index + sizeof index, i).ptr;
    std::string pointer;
    pointer.reserve(base.size() + static_cast<size_t>(end - index));
    pointer.append(base).append(index, static_cast<size_t>(end - index));
    out.emplace_back(v[i], std::move(pointer), file_);
  }
  return out;
}

void Params::finish() const {
  const auto read = [this](const json& v) {
    for (const Asked& a : asked_)
      if (a.value == &v) return a.read;
    return false;
  };
  for (auto it = j_->begin(); it != j_->end(); ++it)
    if (!read(it.value())) {
      // Every key asked for, present or not, is a suggestion.
      std::vector<std::string> known = absent_;
      for (auto m = j_->begin(); m != j_->end(); ++m)
        for (const Asked& a : asked_)
          if (a.value == &m.value()) known.push_back(m.key());
      std::sort(known.begin(), known.end());  // the suggestion's order among equally near keys
      fail(json_pointer_escape(it.key()), unknown_key_message(it.key(), known));
    }
}

}  // namespace softtrace

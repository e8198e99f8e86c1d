// Scene parameters with their location: pbrt's ParameterDictionary idea over nlohmann::json.
// Every read records the key, `finish()` reports keys nobody read (misspellings), and every error
// names the place as `file: /json/pointer: what was expected`.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "math/vec.h"

namespace softtrace {

// `text` with its control characters (bytes below 0x20, and 0x7f) written as JSON escapes,
// "\u0000": a message quotes what the input holds (a key, a type name, a path), and raw, a NUL
// would cut the line short where it is printed as a C string, a newline would break it in two and
// an escape sequence would drive the user's terminal.
std::string printable(const std::string& text);

// Bad input: the message is the one line the user sees.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(const std::string& message) : std::runtime_error(printable(message)) {}
};

class Params {
 public:
  using json = nlohmann::json;

  // `j` must outlive the Params and everything created from it during loading.
  Params(const json& j, std::string pointer, std::shared_ptr<const std::string> file);

  const std::string& pointer() const { return pointer_; }
  // The file named in errors: Params over a copy of this JSON (e.g. one with keys taken out by
  // the renderer) report against the same file.
  const std::shared_ptr<const std::string>& file() const { return file_; }
  const json& raw() const { return *j_; }
  bool has(const std::string& key) const;

  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  double positive(const std::string& key) const;  // finite and > 0
  double positive(const std::string& key, double fallback) const;
  int integer(const std::string& key, int lo, int hi) const;
  int integer(const std::string& key, int lo, int hi, int fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  Vec3 vec3(const std::string& key) const;
  Vec3 vec3(const std::string& key, const Vec3& fallback) const;
  std::vector<Vec3> vec3s(const std::string& key) const;      // a non-empty array of [x, y, z]
  std::vector<double> numbers(const std::string& key) const;  // a non-empty array of numbers
  // A number or an array of `count` numbers (a number is repeated).
  std::vector<double> numbers_or_scalar(const std::string& key, size_t count) const;

  // The raw value of a required key, marked as read, for shapes no typed reader covers.
  const json& get(const std::string& key) const { return at(key); }

  Params object(const std::string& key) const;
  std::vector<Params> objects(const std::string& key) const;  // an array of objects

  // Errors about a key of this object (or the object itself when key is empty). `key` is a
  // relative JSON pointer ("radii/2"); keys from the scene must be escaped first.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  void check(bool ok, const std::string& key, const std::string& what) const {
    if (!ok) fail(key, what);
  }
  // Errors about an element of the array `key`: `index_path` is "i" or "i/j" (array indices,
  // not escaped, so the pointer reads /key/i/j).
  [[noreturn]] void fail_at(const std::string& key, const std::string& index_path,
                            const std::string& what) const;
  void check_at(bool ok, const std::string& key, size_t index, const std::string& what) const {
    if (!ok) fail_at(key, std::to_string(index), what);
  }
  // Reports the first key that no one read, naming the nearest key that was asked for.
  void finish() const;
  // Declares every key this object may have and reports the first other one at once, naming the
  // nearest of `known` and ending with `context` (e.g. " for an ambient light"), so that a
  // misspelled key is reported before a missing one, as the kinds table does for nodes. From
  // then on, reading a key outside `known` is a bug of the loader (std::logic_error): the
  // list is the whole truth, which lets documentation be checked against it.
  void check_keys(const std::vector<std::string>& known, const std::string& context = "") const;

  std::string where(const std::string& key) const;  // "file: /pointer/key"

 private:
  const json& at(const std::string& key) const;  // marks the key used; fails if missing
  // Records `key` as asked for (check_keys' rule) and returns its value, or null when missing.
  const json* lookup(const std::string& key) const;

  // A member of *j_ asked for, by its value's address (the document outlives the Params): the
  // loader asks some 20 times per node of a 1000-component scene, and comparing addresses
  // replaced copying and comparing the key strings.
  struct Asked {
    const json* value;
    bool read;  // by `at` (not only `has`)
  };

  const json* j_;
  std::string pointer_;
  std::shared_ptr<const std::string> file_;
  mutable std::vector<Asked> asked_;         // members asked for, each once
  mutable std::vector<std::string> absent_;  // keys asked for that the object lacks, each once
  mutable std::vector<std::string> known_;   // check_keys' list; empty: any key may be read
};

std::string json_pointer_escape(const std::string& key);
// A JSON value shortened for an error message.
std::string json_excerpt(const nlohmann::json& v);
// "unknown key 'raduis' (did you mean 'radius'?)": the suggestion is the nearest of `known`
// within two edits (insertions, deletions, substitutions, swaps of neighbours), if any.
std::string unknown_key_message(const std::string& key, const std::vector<std::string>& known);

}  // namespace softtrace

#include "scene/json_fast.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <system_error>
#include <vector>

#include "scene/json_nesting.h"

namespace softtrace {

namespace {

using json = nlohmann::json;

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// The powers of ten a double holds exactly, 10^0 to 10^22 (5^22 < 2^53), and the significands it
// holds exactly, up to 2^53: the fast path's limits. kFastDigits: a significand still below it
// takes one more digit without leaving 64 bits.
constexpr int kFastPower = 22;
constexpr double kPowersOfTen[kFastPower + 1] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                 1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
constexpr std::uint64_t kFastSignificand = std::uint64_t(1) << 53;
constexpr std::uint64_t kFastDigits = std::uint64_t(1) << 60;

// Recursive descent over the text, building nlohmann's document in place. Depth is bounded by
// kMaxJsonNesting, as check_json_nesting bounds the located parser's input, so the recursion is.
// Every `false` means "leave it to the located parser", never "the text is wrong".
class FastParser {
 public:
  explicit FastParser(const std::string& text) : p_(text.data()), end_(text.data() + text.size()) {}

  bool document(json& out) { return space() && value(out, 0) && space() && p_ == end_; }

 private:
  // Whitespace and comments, as nlohmann's lexer skips them with comments allowed. A NUL ends a
  // line comment there; such a file is left to it.
  bool space() {
    for (;;) {
      while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
      if (p_ == end_ || *p_ != '/') return true;
      if (end_ - p_ < 2) return false;
      if (p_[1] == '/') {
        for (p_ += 2; p_ < end_ && *p_ != '\n' && *p_ != '\r'; ++p_)
          if (*p_ == '\0') return false;
      } else if (p_[1] == '*') {
        for (p_ += 2;; ++p_) {
          if (end_ - p_ < 2 || *p_ == '\0') return false;
          if (p_[0] == '*' && p_[1] == '/') break;
        }
        p_ += 2;
      } else {
        return false;
      }
    }
  }

  bool value(json& out, int depth) {
    if (p_ == end_) return false;
    switch (*p_) {
      case '{':
        return object(out, depth + 1);
      case '[':
        return array(out, depth + 1);
      case '"': {
        const char* q = string_end();
        if (!q) return false;
        out = std::string(p_ + 1, q);
        p_ = q + 1;
        return true;
      }
      case 't':
        return literal("true", json(true), out);
      case 'f':
        return literal("false", json(false), out);
      case 'n':
        return literal("null", json(nullptr), out);
      default:
        return number(out);
    }
  }

  template <size_t N>
  bool literal(const char (&word)[N], json v, json& out) {
    if (size_t(end_ - p_) < N - 1 || std::memcmp(p_, word, N - 1) != 0) return false;
    p_ += N - 1;
    out = std::move(v);
    return true;
  }

  // The closing quote of the string that opens at p_, or null. Printable ASCII only: escapes and
  // UTF-8 (which the located parser validates) are left to it. The caller constructs the string
  // from the text between the quotes: assigning it to an empty string took the general
  // replacement's path, a fortieth of a 1000-component scene's parse.
  const char* string_end() const {
    const char* q = p_ + 1;
    for (; q < end_ && *q != '"'; ++q) {
      const unsigned char c = static_cast<unsigned char>(*q);
      if (c < 0x20 || c >= 0x80 || c == '\\') return nullptr;
    }
    return q == end_ ? nullptr : q;
  }

  // JSON's number grammar. nlohmann types a token without '.', 'e' or 'E' as unsigned (no sign)
  // or signed (a minus) when it fits 64 bits, and otherwise reads it with strtod; from_chars
  // rounds as strtod does (both correctly). What does not fit, either way, is left to it.
  // A decimal of at most 2^53 in its digits and a power of ten of at most 22 either way is read
  // as one product or quotient of two exact doubles (Clinger's fast path), which IEEE arithmetic
  // rounds correctly, so to from_chars' bits: a scene's coordinates are such decimals, and
  // reading them again in from_chars was a ninth of a 1000-component scene's parse.
  bool number(json& out) {
    const char* start = p_;
    const char* q = p_;
    if (q < end_ && *q == '-') ++q;
    if (q == end_ || !is_digit(*q)) return false;
    std::uint64_t digits = 0;  // the significand's digits, while it stays below kFastDigits
    int scale = 0;             // the power of ten they are multiplied by
    bool exact = true;         // digits (and scale) hold the token's value
    const auto take = [&](char c) {
      if (digits >= kFastDigits) exact = false;
      digits = digits * 10 + std::uint64_t(c - '0');
    };
    if (*q == '0')
      ++q;
    else
      while (q < end_ && is_digit(*q)) take(*q++);
    bool integral = true;
    if (q < end_ && *q == '.') {
      integral = false;
      if (++q == end_ || !is_digit(*q)) return false;
      while (q < end_ && is_digit(*q)) take(*q++), --scale;
    }
    if (q < end_ && (*q == 'e' || *q == 'E')) {
      integral = false;
      bool minus = false;
      if (++q < end_ && (*q == '+' || *q == '-')) minus = *q++ == '-';
      if (q == end_ || !is_digit(*q)) return false;
      int e = 0;
      while (q < end_ && is_digit(*q)) {
        if (e > kFastPower) exact = false;  // stops growing: the token goes to from_chars
        if (exact) e = e * 10 + (*q - '0');
        ++q;
      }
      scale += minus ? -e : e;
    }
    p_ = q;
    if (integral && *start == '-') return read<std::int64_t>(start, q, out);
    if (integral) return read<std::uint64_t>(start, q, out);
    if (exact && digits <= kFastSignificand && scale >= -kFastPower && scale <= kFastPower) {
      const double m = double(digits);
      const double v = scale < 0 ? m / kPowersOfTen[-scale] : m * kPowersOfTen[scale];
      out = *start == '-' ? -v : v;
      return true;
    }
    double v = 0;
    const auto r = std::from_chars(start, q, v);
    if (r.ec != std::errc() || r.ptr != q || !std::isfinite(v) ||
        (v != 0 && std::fpclassify(v) == FP_SUBNORMAL))
      return false;
    out = v;
    return true;
  }

  template <class Int>
  static bool read(const char* start, const char* end, json& out) {
    Int v = 0;
    const auto r = std::from_chars(start, end, v);
    if (r.ec != std::errc() || r.ptr != end) return false;
    out = v;
    return true;
  }

  bool object(json& out, int depth) {
    if (depth > kMaxJsonNesting) return false;
    const int again = seen_before(depth);
    if (again >= 0 && seen_[depth].seen[again].value) {
      const Seen& s = seen_[depth].seen[again];
      out = *s.value;
      p_ += s.size;
      return true;
    }
    const char* start = p_;
    if (!members(out, depth)) return false;
    // Found again by its place: the deeper objects read meanwhile may have moved the rings.
    if (again >= 0)
      seen_[depth].seen[again].value = std::make_unique<json>(out);
    else
      remember(depth, start);
    return true;
  }

  // An object's text read before at the same depth (its bytes from the '{' on, the same bytes
  // the same value), and that value once read twice: a blend's components repeat their
  // potential and distance objects word for word, and a copy of the value costs the allocations
  // of a parse without its scanning. The value is a copy because the document's values move
  // while the arrays that hold them are made.
  struct Seen {
    const char* text = nullptr;
    size_t size = 0;
    std::unique_ptr<json> value;
  };
  static constexpr int kSeenPerDepth = 4;
  struct SeenRing {
    Seen seen[kSeenPerDepth];
    int next = 0;
  };

  // The slot of the text at p_ in its depth's ring, or -1. The texts' ends are compared first:
  // distinct objects of one shape (a cloud's segments) share their first bytes, not their last.
  int seen_before(int depth) const {
    if (size_t(depth) >= seen_.size()) return -1;
    const size_t left = size_t(end_ - p_);
    for (int i = 0; i < kSeenPerDepth; ++i) {
      const Seen& s = seen_[depth].seen[i];
      if (!s.text || s.size > left) continue;
      if (s.size >= sizeof(std::uint64_t)) {
        std::uint64_t a, b;
        std::memcpy(&a, s.text + s.size - sizeof a, sizeof a);
        std::memcpy(&b, p_ + s.size - sizeof b, sizeof b);
        if (a != b) continue;
      }
      if (std::memcmp(s.text, p_, s.size) == 0) return i;
    }
    return -1;
  }

  // In the ring's next slot that holds no value, if any: a text met again stays while objects
  // met once pass (a cloud's potential between its distinct distances).
  void remember(int depth, const char* start) {
    if (size_t(depth) >= seen_.size()) seen_.resize(depth + 1);
    SeenRing& ring = seen_[depth];
    for (int tries = 1; tries < kSeenPerDepth && ring.seen[ring.next].value; ++tries)
      ring.next = (ring.next + 1) % kSeenPerDepth;
    Seen& s = ring.seen[ring.next];
    ring.next = (ring.next + 1) % kSeenPerDepth;
    s.text = start;
    s.size = size_t(p_ - start);
    s.value = nullptr;
  }

  bool members(json& out, int depth) {
    ++p_;
    out = json(json::value_t::object);  // the initializer-list constructor's checks skipped
    auto& members = out.get_ref<json::object_t&>();
    if (!space() || p_ == end_) return false;
    if (*p_ == '}') {
      ++p_;
      return true;
    }
    for (;;) {
      const char* q = *p_ == '"' ? string_end() : nullptr;
      if (!q) return false;
      std::string key(p_ + 1, q);
      p_ = q + 1;
      if (!space() || p_ == end_ || *p_ != ':') return false;
      ++p_;
      const auto placed = members.emplace(std::move(key), nullptr);
      if (!placed.second) return false;  // a repeated key: the located parser names it
      if (!space() || !value(placed.first->second, depth) || !space() || p_ == end_) return false;
      if (*p_ == '}') {
        ++p_;
        return true;
      }
      if (*p_++ != ',' || !space() || p_ == end_) return false;
    }
  }

  // The items go to a stack shared by every open array and then into a vector of their exact
  // size: one allocation per array, where growing it in place took three for an [x, y, z] (and
  // moved the items twice).
  bool array(json& out, int depth) {
    if (depth > kMaxJsonNesting) return false;
    ++p_;
    if (!space() || p_ == end_) return false;
    if (*p_ == ']') {
      ++p_;
      out = json(json::value_t::array);
      return true;
    }
    const size_t base = items_.size();
    for (;;) {
      if (p_ < end_ && (*p_ == '[' || *p_ == '{')) {
        // `value` may grow items_ (a nested array): read into a local, then move it in.
        json item;
        if (!value(item, depth)) return false;
        items_.push_back(std::move(item));
      } else if (!value(items_.emplace_back(), depth)) {  // a scalar, read in its place
        return false;
      }
      if (!space() || p_ == end_) return false;
      if (*p_ == ']') {
        ++p_;
        break;
      }
      if (*p_++ != ',' || !space()) return false;
    }
    out = json(json::value_t::array);
    auto& items = out.get_ref<json::array_t&>();
    items.reserve(items_.size() - base);
    for (size_t i = base; i < items_.size(); ++i) items.push_back(std::move(items_[i]));
    items_.resize(base);
    return true;
  }

  const char* p_;
  const char* end_;
  std::vector<json> items_;     // the items of the arrays being read, innermost last
  std::vector<SeenRing> seen_;  // by depth
};

}  // namespace

bool parse_json_fast(const std::string& text, json& out) {
  return FastParser(text).document(out);
}

}  // namespace softtrace

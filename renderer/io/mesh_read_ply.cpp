// PLY (mesh_read.h says what is read): the header's elements and properties, then their records,
// as text or as binary of either byte order.
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

#include "io/mesh_read.h"

namespace softtrace {

namespace {

enum class Type { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

size_t type_size(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::Uint8:
      return 1;
    case Type::Int16:
    case Type::Uint16:
      return 2;
    case Type::Int32:
    case Type::Uint32:
    case Type::Float32:
      return 4;
    case Type::Float64:
      return 8;
  }
  return 0;
}

bool integral(Type t) {
  return t != Type::Float32 && t != Type::Float64;
}

bool type_named(std::string_view name, Type& t) {
  static const std::pair<const char*, Type> names[] = {
      {"char", Type::Int8},      {"int8", Type::Int8},       {"uchar", Type::Uint8},
      {"uint8", Type::Uint8},    {"short", Type::Int16},     {"int16", Type::Int16},
      {"ushort", Type::Uint16},  {"uint16", Type::Uint16},   {"int", Type::Int32},
      {"int32", Type::Int32},    {"uint", Type::Uint32},     {"uint32", Type::Uint32},
      {"float", Type::Float32},  {"float32", Type::Float32}, {"double", Type::Float64},
      {"float64", Type::Float64}};
  for (const auto& [n, type] : names)
    if (name == n) {
      t = type;
      return true;
    }
  return false;
}

struct Property {
  std::string name;
  bool list = false;
  Type count = Type::Uint8, item = Type::Float32;
};

struct Element {
  std::string name;
  size_t count = 0;
  size_t line = 0;  // of its header line
  std::vector<Property> properties;
};

enum class Format { Ascii, Little, Big };

class PlyReader {
 public:
  PlyReader(const std::string& bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  MeshData read() {
    header();
    for (const Element& e : elements_) body(e);
    if (format_ == Format::Ascii) {
      std::string_view t = token();
      if (!t.empty())
        fail_line("data past the last element: '" + std::string(t.substr(0, 40)) + "'");
    }
    if (mesh_.faces.empty()) fail_line("no faces: the file holds no surface");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail_line(const std::string& what) const {
    throw MeshReadError(name_ + ":" + std::to_string(line_) + ": " + what);
  }
  // In the body: text has lines, binary has records.
  [[noreturn]] void fail_record(const Element& e, size_t i, const std::string& what) const {
    if (format_ == Format::Ascii) fail_line(what);
    throw MeshReadError(name_ + ": " + e.name + " " + std::to_string(i) + ": " + what);
  }

  // The next header line's tokens.
  std::vector<std::string_view> header_line() {
    if (at_ >= bytes_.size()) fail_line("the file ends in the header (no end_header)");
    ++line_;
    size_t end = bytes_.find('\n', at_);
    if (end == std::string::npos) end = bytes_.size();
    std::string_view rest = std::string_view(bytes_).substr(at_, end - at_);
    at_ = end + 1;
    std::vector<std::string_view> tokens;
    while (true) {
      size_t b = 0;
      while (b < rest.size() && (rest[b] == ' ' || rest[b] == '\t' || rest[b] == '\r')) ++b;
      size_t e = b;
      while (e < rest.size() && rest[e] != ' ' && rest[e] != '\t' && rest[e] != '\r') ++e;
      if (b == e) break;
      tokens.push_back(rest.substr(b, e - b));
      rest.remove_prefix(e);
    }
    return tokens;
  }

  Type type(std::string_view name) const {
    Type t;
    if (!type_named(name, t))
      fail_line("unknown property type '" + std::string(name.substr(0, 40)) + "'");
    return t;
  }

  void header() {
    std::vector<std::string_view> t = header_line();
    if (t.size() != 1 || t[0] != "ply") fail_line("not a PLY file (it must start with 'ply')");
    bool has_format = false;
    while (true) {
      t = header_line();
      if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
      if (t[0] == "end_header") break;
      if (t[0] == "format") {
        if (t.size() != 3 || t[2] != "1.0") fail_line("expected 'format <type> 1.0'");
        if (t[1] == "ascii")
          format_ = Format::Ascii;
        else if (t[1] == "binary_little_endian")
          format_ = Format::Little;
        else if (t[1] == "binary_big_endian")
          format_ = Format::Big;
        else
          fail_line("unknown format '" + std::string(t[1].substr(0, 40)) + "'");
        has_format = true;
      } else if (t[0] == "element") {
        if (t.size() != 3) fail_line("expected 'element <name> <count>'");
        Element e;
        e.name = std::string(t[1]);
        e.line = line_;
        unsigned long long count = 0;
        const auto r = std::from_chars(t[2].data(), t[2].data() + t[2].size(), count);
        if (r.ec != std::errc() || r.ptr != t[2].data() + t[2].size())
          fail_line("expected a count, not '" + std::string(t[2].substr(0, 40)) + "'");
        for (const Element& before : elements_)
          if (before.name == e.name) fail_line("a second element '" + e.name + "'");
        const size_t most = e.name == "face"     ? kMaxMeshTriangles
                            : e.name == "vertex" ? kMaxMeshVertices
                                                 : kMaxMeshFileBytes;
        if (count > most)
          fail_line(std::to_string(count) + " records of element '" + e.name + "': more than " +
                    std::to_string(most));
        e.count = size_t(count);
        elements_.push_back(e);
      } else if (t[0] == "property") {
        if (elements_.empty()) fail_line("a property before any element");
        Property p;
        if (t.size() == 5 && t[1] == "list") {
          p.list = true;
          p.count = type(t[2]);
          p.item = type(t[3]);
          if (!integral(p.count)) fail_line("a list's count must be of an integer type");
          p.name = std::string(t[4]);
        } else if (t.size() == 3) {
          p.item = type(t[1]);
          p.name = std::string(t[2]);
        } else {
          fail_line("expected 'property <type> <name>' or 'property list <type> <type> <name>'");
        }
        for (const Property& before : elements_.back().properties)
          if (before.name == p.name) fail_line("a second property '" + p.name + "'");
        elements_.back().properties.push_back(p);
      } else {
        fail_line("unknown header line '" + std::string(t[0].substr(0, 40)) + "'");
      }
    }
    if (!has_format) fail_line("no 'format' line in the header");
    const size_t end_header = line_;
    const Element* vertex = find("vertex");
    const Element* face = find("face");
    if (!vertex) fail_line("no 'vertex' element");
    if (!face) fail_line("no 'face' element");
    for (const char* axis : {"x", "y", "z"}) {
      const Property* p = find(*vertex, axis);
      if (!p || p->list) {
        line_ = vertex->line;
        fail_line(std::string("the vertex element has no scalar property '") + axis + "'");
      }
    }
    int normals = 0;
    for (const char* axis : {"nx", "ny", "nz"})
      if (const Property* p = find(*vertex, axis); p && !p->list) ++normals;
    smooth_ = normals == 3;
    const Property* indices = find(*face, "vertex_indices");
    if (!indices) indices = find(*face, "vertex_index");
    if (!indices || !indices->list || !integral(indices->item)) {
      line_ = face->line;
      fail_line("the face element has no integer list 'vertex_indices'");
    }
    vertex_count_ = vertex->count;
    for (const Element& e : elements_) {
      // Each record takes at least this many bytes (text: a digit and a separator per value).
      size_t least = 0;
      for (const Property& p : e.properties)
        least += format_ == Format::Ascii ? 2 : p.list ? type_size(p.count) : type_size(p.item);
      if (least > 0 && e.count > (bytes_.size() - std::min(at_, bytes_.size())) / least) {
        line_ = e.line;
        fail_line("the file is too short for " + std::to_string(e.count) + " records of element '" +
                  e.name + "'");
      }
    }
    line_ = end_header + 1;  // the body's first line (text): token() counts the ones after it
  }

  const Element* find(const std::string& name) const {
    for (const Element& e : elements_)
      if (e.name == name) return &e;
    return nullptr;
  }
  static const Property* find(const Element& e, const std::string& name) {
    for (const Property& p : e.properties)
      if (p.name == name) return &p;
    return nullptr;
  }

  // The next text token, counting lines; empty at the end of the file.
  std::string_view token() {
    const size_t line = line_;  // at the end of the file: the last line with a token
    while (at_ < bytes_.size()) {
      const char c = bytes_[at_];
      if (c == '\n')
        ++line_;
      else if (c != ' ' && c != '\t' && c != '\r')
        break;
      ++at_;
    }
    const size_t b = at_;
    while (at_ < bytes_.size() && bytes_[at_] != ' ' && bytes_[at_] != '\t' &&
           bytes_[at_] != '\r' && bytes_[at_] != '\n')
      ++at_;
    if (b == at_) line_ = line;
    return std::string_view(bytes_).substr(b, at_ - b);
  }

  double value(Type type, const Element& e, size_t i) {
    if (format_ == Format::Ascii) {
      const std::string_view t = token();
      if (t.empty()) fail_line("the file ends inside " + e.name + " " + std::to_string(i));
      const std::string_view digits = t[0] == '+' ? t.substr(1) : t;
      double v = 0;
      const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), v);
      if (digits.empty() || digits[0] == '+' || r.ec != std::errc() ||
          r.ptr != digits.data() + digits.size())
        fail_line("expected a number, not '" + std::string(t.substr(0, 40)) + "'");
      if (!std::isfinite(v)) fail_line("expected a finite number, not '" + std::string(t) + "'");
      if (integral(type) && v != std::floor(v))
        fail_line("expected an integer, not '" + std::string(t.substr(0, 40)) + "'");
      return v;
    }
    const size_t n = type_size(type);
    if (bytes_.size() - std::min(at_, bytes_.size()) < n)
      fail_record(e, i, "the file ends inside it");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + at_, n);
    at_ += n;
    const bool swap = format_ == Format::Big;  // the machine is little-endian (x86-64, arm64)
    if (swap)
      for (size_t k = 0; k < n / 2; ++k) std::swap(b[k], b[n - 1 - k]);
    switch (type) {
      case Type::Int8: {
        int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case Type::Uint8:
        return b[0];
      case Type::Int16: {
        int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Type::Uint16: {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Type::Int32: {
        int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::Uint32: {
        uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::Float32: {
        float v;
        std::memcpy(&v, b, 4);
        if (!std::isfinite(v)) fail_record(e, i, "a value that is not a finite number");
        return v;
      }
      case Type::Float64: {
        double v;
        std::memcpy(&v, b, 8);
        if (!std::isfinite(v)) fail_record(e, i, "a value that is not a finite number");
        return v;
      }
    }
    return 0;
  }

  void body(const Element& e) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    if (is_vertex) {
      mesh_.positions.reserve(e.count);
      if (smooth_) mesh_.normals.reserve(e.count);
    }
    if (is_face) mesh_.faces.reserve(e.count);
    std::vector<uint32_t> polygon;
    for (size_t i = 0; i < e.count; ++i) {
      Vec3 position{0, 0, 0}, normal{0, 0, 0};
      for (const Property& p : e.properties) {
        if (!p.list) {
          const double v = value(p.item, e, i);
          if (is_vertex) {
            static const char* const kAxes[6] = {"x", "y", "z", "nx", "ny", "nz"};
            for (int k = 0; k < 6; ++k)
              if (p.name == kAxes[k]) (k < 3 ? position[k] : normal[k - 3]) = v;
          }
          continue;
        }
        const double count = value(p.count, e, i);
        if (count < 0) fail_record(e, i, "a list of negative length");
        const bool indices = is_face && (p.name == "vertex_indices" || p.name == "vertex_index");
        polygon.clear();
        for (double k = 0; k < count; ++k) {
          const double v = value(p.item, e, i);
          if (!indices) continue;
          if (v < 0 || v >= double(vertex_count_))
            fail_record(e, i,
                        "vertex index " + std::to_string(static_cast<long long>(v)) +
                            " out of range (the file has " + std::to_string(vertex_count_) +
                            " vertices)");
          polygon.push_back(uint32_t(v));
        }
        if (!indices) continue;
        if (polygon.size() < 3)
          fail_record(e, i,
                      "a face of " + std::to_string(polygon.size()) + " corners (at least 3)");
        if (mesh_.faces.size() + polygon.size() - 2 > kMaxMeshTriangles)
          fail_record(e, i, "more than " + std::to_string(kMaxMeshTriangles) + " triangles");
        for (size_t k = 1; k + 1 < polygon.size(); ++k)
          mesh_.faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
      }
      if (is_vertex) {
        mesh_.positions.push_back(position);
        if (smooth_) mesh_.normals.push_back(normal);
      }
    }
    if (is_face && smooth_) mesh_.face_normals = mesh_.faces;
    if (is_vertex && smooth_ && !mesh_.faces.empty()) mesh_.face_normals = mesh_.faces;
  }

  const std::string& bytes_;
  const std::string& name_;
  size_t at_ = 0, line_ = 0;
  Format format_ = Format::Ascii;
  std::vector<Element> elements_;
  bool smooth_ = false;
  size_t vertex_count_ = 0;
  MeshData mesh_;
};

}  // namespace

MeshData read_ply(const std::string& bytes, const std::string& name) {
  return PlyReader(bytes, name).read();
}

}  // namespace softtrace

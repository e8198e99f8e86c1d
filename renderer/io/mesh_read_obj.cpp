// Wavefront OBJ's polygonal subset (mesh_read.h says which statements).
#include <charconv>
#include <cmath>
#include <string_view>

#include "io/mesh_read.h"

namespace softtrace {

namespace {

// Statements that carry nothing a triangle mesh needs (texture coordinates, groups, smoothing
// groups, materials, lines, points, display attributes).
bool skipped(std::string_view keyword) {
  for (const char* k :
       {"vt", "vp", "g", "o", "s", "mg", "usemtl", "mtllib", "l", "p", "lod", "bevel", "c_interp",
        "d_interp", "maplib", "usemap", "shadow_obj", "trace_obj"})
    if (keyword == k) return true;
  return false;
}

bool free_form(std::string_view keyword) {
  for (const char* k : {"cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim",
                        "hole", "scrv", "sp", "end", "con", "ctech", "stech"})
    if (keyword == k) return true;
  return false;
}

class ObjReader {
 public:
  ObjReader(const std::string& bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  MeshData read() {
    size_t at = 0;
    while (at < bytes_.size()) {
      ++line_;
      size_t end = bytes_.find('\n', at);
      if (end == std::string::npos) end = bytes_.size();
      statement(std::string_view(bytes_).substr(at, end - at));
      at = end + 1;
    }
    if (max_v_ > mesh_.positions.size())
      fail_at(max_v_line_, "vertex index " + std::to_string(max_v_) +
                               " out of range (the file has " +
                               std::to_string(mesh_.positions.size()) + " vertices)");
    if (max_vn_ > mesh_.normals.size())
      fail_at(max_vn_line_, "normal index " + std::to_string(max_vn_) +
                                " out of range (the file has " +
                                std::to_string(mesh_.normals.size()) + " normals)");
    if (mesh_.faces.empty()) fail_at(line_, "no faces: the file holds no surface");
    if (!smooth_) {
      mesh_.face_normals.clear();
      mesh_.normals.clear();
    }
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail_at(size_t line, const std::string& what) const {
    throw MeshReadError(name_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(line_, what); }

  // The next whitespace-separated token of `rest`, taken off it; empty at the end.
  static std::string_view token(std::string_view& rest) {
    size_t b = 0;
    while (b < rest.size() && (rest[b] == ' ' || rest[b] == '\t' || rest[b] == '\r')) ++b;
    size_t e = b;
    while (e < rest.size() && rest[e] != ' ' && rest[e] != '\t' && rest[e] != '\r') ++e;
    const std::string_view t = rest.substr(b, e - b);
    rest.remove_prefix(e);
    return t;
  }

  double number(std::string_view t) const {
    const std::string_view digits = !t.empty() && t[0] == '+' ? t.substr(1) : t;
    double v = 0;
    const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (digits.empty() || digits[0] == '+' || (digits != t && digits[0] == '-') ||
        r.ec != std::errc() || r.ptr != digits.data() + digits.size())
      fail("expected a number, not '" + std::string(t.substr(0, 40)) + "'");
    if (!std::isfinite(v)) fail("expected a finite number, not '" + std::string(t) + "'");
    return v;
  }

  // A point or direction: 3 numbers, up to `most` in all (the rest read and ignored).
  Vec3 vector(std::string_view rest, size_t most, const char* what) const {
    double v[7];
    size_t n = 0;
    for (std::string_view t = token(rest); !t.empty(); t = token(rest)) {
      if (n == most)
        fail(std::string("expected at most ") + std::to_string(most) + " numbers for " + what);
      v[n++] = number(t);
    }
    if (n < 3) fail(std::string("expected 3 numbers for ") + what);
    return {v[0], v[1], v[2]};
  }

  // A 1-based or negative (relative to the `count` so far) index, 0-based out; `max`/`max_line`
  // keep the largest positive one, checked once every vertex is read.
  uint32_t index(std::string_view t, size_t count, const char* what, size_t& max,
                 size_t& max_line) const {
    long long i = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), i);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(std::string("expected a ") + what + " index, not '" + std::string(t.substr(0, 40)) +
           "'");
    if (i == 0) fail(std::string("a ") + what + " index of 0 (indices start at 1)");
    if (i < 0) {
      if (static_cast<unsigned long long>(-(i + 1)) >= count)
        fail(std::string(what) + " index " + std::to_string(i) + " out of range (only " +
             std::to_string(count) + " before it)");
      return uint32_t(count - static_cast<unsigned long long>(-(i + 1)) - 1);
    }
    if (static_cast<unsigned long long>(i) > kMaxMeshVertices)
      fail(std::string(what) + " index " + std::to_string(i) + " out of range (at most " +
           std::to_string(kMaxMeshVertices) + ")");
    if (size_t(i) > max) max = size_t(i), max_line = line_;
    return uint32_t(i - 1);
  }

  void face(std::string_view rest) {
    corners_.clear();
    bool normals = true;
    for (std::string_view t = token(rest); !t.empty(); t = token(rest)) {
      const size_t s1 = t.find('/');
      const std::string_view v = t.substr(0, s1);
      std::string_view vt, vn;
      if (s1 != std::string_view::npos) {
        const std::string_view after = t.substr(s1 + 1);
        const size_t s2 = after.find('/');
        vt = after.substr(0, s2);
        if (s2 != std::string_view::npos) vn = after.substr(s2 + 1);
      }
      if (!vt.empty()) {  // checked for form only: texture coordinates are not kept
        long long unused = 0;
        const auto r = std::from_chars(vt.data(), vt.data() + vt.size(), unused);
        if (r.ec != std::errc() || r.ptr != vt.data() + vt.size() || unused == 0)
          fail("expected a texture index, not '" + std::string(vt.substr(0, 40)) + "'");
      }
      Corner c{index(v, mesh_.positions.size(), "vertex", max_v_, max_v_line_), 0};
      if (vn.empty())
        normals = false;
      else
        c.vn = index(vn, mesh_.normals.size(), "normal", max_vn_, max_vn_line_);
      corners_.push_back(c);
      if (corners_.size() > kMaxMeshTriangles) fail("a face with too many corners");
    }
    if (corners_.size() < 3)
      fail("expected a face of at least 3 corners, not " + std::to_string(corners_.size()));
    if (mesh_.faces.size() + corners_.size() - 2 > kMaxMeshTriangles)
      fail("more than " + std::to_string(kMaxMeshTriangles) + " triangles");
    if (!normals) smooth_ = false;
    for (size_t k = 1; k + 1 < corners_.size(); ++k) {
      mesh_.faces.push_back({corners_[0].v, corners_[k].v, corners_[k + 1].v});
      if (smooth_)
        mesh_.face_normals.push_back({corners_[0].vn, corners_[k].vn, corners_[k + 1].vn});
    }
  }

  void statement(std::string_view line) {
    if (line.find('\0') != std::string_view::npos) fail("a NUL byte: not a text file");
    std::string_view rest = line;
    const std::string_view keyword = token(rest);
    if (keyword.empty() || keyword[0] == '#') return;
    if (keyword == "v") {
      if (mesh_.positions.size() == kMaxMeshVertices)
        fail("more than " + std::to_string(kMaxMeshVertices) + " vertices");
      mesh_.positions.push_back(vector(rest, 7, "a vertex"));
    } else if (keyword == "vn") {
      if (mesh_.normals.size() == kMaxMeshVertices)
        fail("more than " + std::to_string(kMaxMeshVertices) + " normals");
      mesh_.normals.push_back(vector(rest, 3, "a normal"));
    } else if (keyword == "f" || keyword == "fo") {
      face(rest);
    } else if (free_form(keyword)) {
      fail("free-form geometry ('" + std::string(keyword) + "') is not supported: triangulate it");
    } else if (!skipped(keyword)) {
      fail("unknown statement '" + std::string(keyword.substr(0, 40)) + "'");
    }
  }

  struct Corner {
    uint32_t v, vn;
  };
  const std::string& bytes_;
  const std::string& name_;
  size_t line_ = 0;
  MeshData mesh_;
  bool smooth_ = true;  // every face so far has a normal at every corner
  std::vector<Corner> corners_;
  size_t max_v_ = 0, max_v_line_ = 0, max_vn_ = 0, max_vn_line_ = 0;
};

}  // namespace

MeshData read_obj(const std::string& bytes, const std::string& name) {
  return ObjReader(bytes, name).read();
}

}  // namespace softtrace

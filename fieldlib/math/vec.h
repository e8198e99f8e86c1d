// Small 3-vector and 3x3 rotation used throughout fieldlib; double precision everywhere.
#pragma once

#include <algorithm>
#include <cmath>

namespace softtrace {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
};

constexpr Vec3 operator*(double s, const Vec3& v) {
  return v * s;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& v) {
  return std::sqrt(dot(v, v));
}
inline Vec3 normalize(const Vec3& v) {
  return v / length(v);
}
// The largest component's magnitude (the scale of a point's coordinates, for rounding).
inline double max_abs(const Vec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}
inline bool isfinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Row-major rotation matrix; rows are orthonormal so the transpose is the inverse.
struct Mat3 {
  Vec3 r[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  Vec3 operator*(const Vec3& v) const { return {dot(r[0], v), dot(r[1], v), dot(r[2], v)}; }
  Vec3 transposed_times(const Vec3& v) const { return r[0] * v.x + r[1] * v.y + r[2] * v.z; }

  // Rodrigues' formula; `axis` need not be unit length but must be non-zero.
  static Mat3 rotation(const Vec3& axis, double degrees);
};

inline Mat3 Mat3::rotation(const Vec3& axis, double degrees) {
  const Vec3 a = normalize(axis);
  const double th = degrees * M_PI / 180.0, c = std::cos(th), s = std::sin(th), t = 1 - c;
  Mat3 m;
  m.r[0] = {t * a.x * a.x + c, t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y};
  m.r[1] = {t * a.x * a.y + s * a.z, t * a.y * a.y + c, t * a.y * a.z - s * a.x};
  m.r[2] = {t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c};
  return m;
}

}  // namespace softtrace

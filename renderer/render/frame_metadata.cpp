#include "render/frame_metadata.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>

namespace softtrace {

namespace {

using Matrix = double[4][4];

void multiply(const Matrix a, const Matrix b, Matrix out) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      out[i][j] = 0;
      for (int k = 0; k < 4; ++k) out[i][j] += a[i][k] * b[k][j];
    }
}

std::array<float, 16> to_floats(const Matrix m) {
  std::array<float, 16> f{};
  for (int i = 0; i < 16; ++i) f[i] = float(m[i / 4][i % 4]);
  return f;
}

}  // namespace

std::string hex64(uint64_t value) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
  return buf;
}

std::string fnv1a64_hex(const std::string& bytes) {
  return hex64(fnv1a(bytes));
}

FrameInfo frame_info(const Scene& scene, int full_width, int full_height, bool with_hash) {
  FrameInfo info;
  info.scene_name = std::filesystem::path(scene.path).stem().string();
  if (with_hash) info.scene_hash = hex64(scene.file_hash());
  info.spp = scene.image.spp;
  info.background = scene.background;

  // The same frame as ViewCamera (camera.h).
  const Camera& c = scene.camera;
  const Vec3 f = normalize(c.target - c.eye), r = normalize(cross(f, c.up)), u = cross(r, f);
  const Matrix world_to_camera = {{r[0], u[0], f[0], 0},
                                  {r[1], u[1], f[1], 0},
                                  {r[2], u[2], f[2], 0},
                                  {-dot(c.eye, r), -dot(c.eye, u), -dot(c.eye, f), 1}};
  const double t = std::tan(0.5 * c.fov * M_PI / 180.0);
  const double aspect = c.aspect > 0 ? c.aspect : double(full_width) / full_height;
  // x_ndc = 0.5 + 0.5 x/(z t aspect), y_ndc = 0.5 - 0.5 y/(z t): homogeneous with w = z.
  const Matrix perspective = {
      {0.5 / (t * aspect), 0, 0, 0}, {0, -0.5 / t, 0, 0}, {0.5, 0.5, 0, 1}, {0, 0, 1, 0}};
  // Orthographic, h = |target - eye| t the view's half height: x_ndc = 0.5 + 0.5 x/(h aspect),
  // y_ndc = 0.5 - 0.5 y/h, w = 1, NDC z = z.
  const double h = t * length(c.target - c.eye);
  const Matrix orthographic = {
      {0.5 / (h * aspect), 0, 0, 0}, {0, -0.5 / h, 0, 0}, {0, 0, 1, 0}, {0.5, 0.5, 0, 1}};
  Matrix world_to_ndc;
  multiply(world_to_camera,
           c.projection == Camera::Projection::Orthographic ? orthographic : perspective,
           world_to_ndc);
  info.world_to_camera = to_floats(world_to_camera);
  info.world_to_ndc = to_floats(world_to_ndc);
  return info;
}

}  // namespace softtrace

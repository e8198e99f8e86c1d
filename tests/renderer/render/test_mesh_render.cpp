// The consumer check: the Fig. 12(b) blend meshed on a 256-cell lattice, written as GLB,
// read back (glb_read.h, not the writer's code), put into Embree as plain triangles and seen
// through the scene's camera, against softtrace's own render of the field (the renderer's
// EmbreeScene and tracers). Silhouettes, depths and Lambert shading from the GLB's normals must
// agree to what a mesh of cell size h can: a depth within a cell, a silhouette within a pixel.
#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "glb_read.h"
#include "io/mesh_file.h"
#include "mesh/mesh.h"
#include "model/program_builder.h"
#include "render/camera.h"
#include "render/frame.h"
#include "trace/embree_scene.h"

namespace softtrace {
namespace {

TEST(MeshRender, Fig12bGlbThroughEmbreeMatchesTheFieldsRender) {
  const Scene scene = load_scene(SOFTTRACE_SOURCE_DIR "/scenes/fig000_12b_soft_blend.json");
  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& o = scene.objects[0];
  const Program p = compile(*o.field);
  MeshOptions opt;
  opt.cells = 256;
  opt.threads = 2;
  const Mesh m = mesh({&p, o.iso, o.inside_sign}, o.bounds, opt);
  std::filesystem::create_directories(SOFTTRACE_TEST_TMP);
  const std::string path = SOFTTRACE_TEST_TMP "/fig12b.glb";
  write_mesh(path, m);
  const glb::Glb g = glb::read(path);
  ASSERT_EQ(g.positions.size(), m.vertices.size());
  ASSERT_EQ(g.index_type, 5125);  // more than 65,535 vertices

  // The GLB as Embree triangles.
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene rtc = rtcNewScene(device);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), g.positions.size()));
  for (size_t i = 0; i < g.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) vb[3 * i + k] = float(g.positions[i][k]);
  auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                            RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                            g.indices.size() / 3));
  std::copy(g.indices.begin(), g.indices.end(), ib);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(rtc, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(rtc);

  const TracedScene field(scene, LipschitzMode::Local);
  constexpr int kW = 160, kH = 120;
  const ViewCamera camera(scene.camera, kW, kH);
  const Vec3 light = normalize(Vec3{1, -1, 2});
  std::vector<int> field_hit(kW * kH), mesh_hit(kW * kH);
  std::vector<double> field_t(kW * kH), mesh_t(kW * kH), field_shade(kW * kH), mesh_shade(kW * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int i = y * kW + x;
      const Ray ray = camera.generate(x + 0.5, y + 0.5);
      const TraceHit h = field.embree.intersect(ray, 0, std::numeric_limits<double>::infinity());
      field_hit[i] = h.hit;
      if (h.hit) {
        field_t[i] = h.t;
        const Vec3 n = field.tracers[0].normal(ray.o + ray.d * h.t);
        field_shade[i] = std::max(0.0, dot(n, light));
      }
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      RTCRayHit rh{};
      rh.ray.org_x = float(ray.o.x), rh.ray.org_y = float(ray.o.y), rh.ray.org_z = float(ray.o.z);
      rh.ray.dir_x = float(ray.d.x), rh.ray.dir_y = float(ray.d.y), rh.ray.dir_z = float(ray.d.z);
      rh.ray.tnear = 0;
      rh.ray.tfar = INFINITY;
      rh.ray.mask = 0xFFFFFFFF;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(rtc, &ctx, &rh);
      mesh_hit[i] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      if (mesh_hit[i]) {
        mesh_t[i] = rh.ray.tfar;
        const uint32_t* t = &g.indices[3 * size_t(rh.hit.primID)];
        const double u = rh.hit.u, v = rh.hit.v;
        const Vec3 n =
            normalize(g.normals[t[0]] * (1 - u - v) + g.normals[t[1]] * u + g.normals[t[2]] * v);
        mesh_shade[i] = std::max(0.0, dot(n, light));
      }
    }
  rtcReleaseScene(rtc);
  rtcReleaseDevice(device);

  // Silhouettes: a pixel may differ only next to an edge of the field's own silhouette.
  long hits = 0, inner_mismatch = 0, both = 0, deep = 0;
  double shade_error = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int i = y * kW + x;
      hits += field_hit[i];
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = std::clamp(x + dx, 0, kW - 1), yy = std::clamp(y + dy, 0, kH - 1);
          edge |= field_hit[yy * kW + xx] != field_hit[i];
        }
      if (field_hit[i] != mesh_hit[i] && !edge) ++inner_mismatch;
      if (field_hit[i] && mesh_hit[i] && !edge) {
        ++both;
        deep += std::abs(mesh_t[i] - field_t[i]) > m.voxel;
        shade_error += std::abs(mesh_shade[i] - field_shade[i]);
      }
    }
  ASSERT_GT(hits, kW * kH / 10) << "the blend should fill a good part of the frame";
  EXPECT_EQ(inner_mismatch, 0) << "silhouettes differ by more than a pixel";
  EXPECT_LE(deep, both / 1000) << "depths further apart than a cell";
  EXPECT_LE(shade_error / double(both), 0.01) << "mean Lambert shading apart by more than 1%";
  RecordProperty("pixels_compared", int(both));
  RecordProperty("mean_shade_error_x1e6", int(1e6 * shade_error / double(both)));
}

}  // namespace
}  // namespace softtrace

// The mesher's guarantees (mesh/mesh.h) on every scene: closed, manifold, oriented outward, no
// degenerate face, vertices on the surface, and the enclosed volume against Monte Carlo.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/batch.h"
#include "mesh/mesh.h"
#include "mesh_check.h"
#include "mesh_scenes.h"
#include "model/program_builder.h"

namespace softtrace {
namespace {

using mesh_scenes::Case;

Mesh mesh_case(const Case& c, const Program& p, int cells, int threads) {
  const SceneObject& o = c.scene->objects[c.object];
  MeshOptions opt;
  opt.cells = cells;
  opt.threads = threads;
  return mesh({&p, o.iso, o.inside_sign}, o.bounds, opt);
}

// A cap vertex lies on the lattice box's face to within the edge solve's tolerance (1e-5 of an
// edge of at most sqrt 3 cells).
bool on_cap(const Mesh& m, const Vec3& v) {
  for (int a = 0; a < 3; ++a)
    if (std::abs(v[a] - m.lattice.lo[a]) <= 1e-4 * m.voxel ||
        std::abs(v[a] - m.lattice.hi[a]) <= 1e-4 * m.voxel)
      return true;
  return false;
}

class MeshScenes : public ::testing::TestWithParam<Case> {};

TEST_P(MeshScenes, ClosedManifoldOrientedAndOnTheSurface) {
  const Case& c = GetParam();
  const SceneObject& o = c.scene->objects[c.object];
  const Program p = compile(*o.field);
  const Mesh m = mesh_case(c, p, 48, 2);
  ASSERT_GT(m.faces.size(), 0u) << "no surface in the object's bounds";
  ASSERT_EQ(m.normals.size(), m.vertices.size());
  ASSERT_EQ(m.colors.size(), m.vertices.size());

  const mesh_check::Report r = mesh_check::check(m);
  EXPECT_EQ(r.boundary_edges, 0) << r.first_problem;
  EXPECT_EQ(r.nonmanifold_edges, 0) << r.first_problem;
  EXPECT_EQ(r.misoriented_edges, 0) << r.first_problem;
  EXPECT_EQ(r.degenerate_faces, 0) << r.first_problem;
  EXPECT_EQ(r.odd_euler, 0) << r.first_problem;
  EXPECT_GT(enclosed_volume(m), 0) << "faces wound inward";

  // |f - iso| / |grad f| in cells, and normals along -inside_sign grad f, off the cap.
  Workspace ws;
  double worst = 0;
  long checked = 0, against = 0;
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    EXPECT_NEAR(length(m.normals[i]), 1, 1e-12);
    if (on_cap(m, m.vertices[i])) continue;
    Vec3 g;
    const double f = evaluate(p, m.vertices[i], &g, ws);
    const double len = length(g);
    if (!(len > 0) || !std::isfinite(len)) continue;
    worst = std::max(worst, std::abs(f - o.iso) / len / m.voxel);
    ++checked;
    against += dot(m.normals[i], g) * -o.inside_sign <= 0;
  }
  EXPECT_LE(worst, 1e-3) << "a vertex off the surface";
  EXPECT_EQ(against, 0) << "normals not along the outward gradient";
  // A slab whose faces are its bounds' (the wheel scene's floor) is all cap.
  if (checked == 0) GTEST_SKIP() << "every vertex lies on the cap: no vertex of the field to check";
}

INSTANTIATE_TEST_SUITE_P(Scenes, MeshScenes, ::testing::ValuesIn(mesh_scenes::all_cases()),
                         [](const auto& info) { return mesh_scenes::test_name(info.param); });

// The volume the mesh encloses against a Monte Carlo estimate of the solid's (a million points
// in the lattice's box: a standard error near 0.2% for these fill fractions).
class MeshVolume : public ::testing::TestWithParam<const char*> {};

TEST_P(MeshVolume, WithinOnePercentOfMonteCarlo) {
  const Case* found = nullptr;
  const auto cases = mesh_scenes::all_cases();
  for (const Case& c : cases)
    if (c.name == GetParam()) found = &c;
  ASSERT_NE(found, nullptr);
  const SceneObject& o = found->scene->objects[found->object];
  const Program p = compile(*o.field);
  const Mesh m = mesh_case(*found, p, 128, 2);
  const double volume = enclosed_volume(m);

  constexpr size_t kSamples = 1000000;
  std::mt19937_64 rng(7);
  std::vector<double> xyz(3 * kSamples), f(kSamples);
  for (size_t i = 0; i < kSamples; ++i)
    for (int a = 0; a < 3; ++a)
      xyz[3 * i + a] =
          std::uniform_real_distribution<double>(m.lattice.lo[a], m.lattice.hi[a])(rng);
  Workspace ws;
  eval_points(p, xyz.data(), kSamples, f.data(), nullptr, ws);
  size_t in = 0;
  for (double v : f) in += o.inside_sign > 0 ? v >= o.iso : v <= o.iso;
  const Vec3 e = m.lattice.extent();
  const double estimate = double(in) / kSamples * e.x * e.y * e.z;
  EXPECT_NEAR(volume, estimate, 0.01 * estimate);
}

INSTANTIATE_TEST_SUITE_P(Scenes, MeshVolume,
                         ::testing::Values("fig000_12b_soft_blend.json#0", "tracer_2#0",
                                           "tracer_3#0", "fig003_9_wheel.json#0"),
                         [](const auto& info) {
                           return mesh_scenes::test_name({info.param, nullptr, 0});
                         });

const Case& blobs() {
  static const auto cases = mesh_scenes::all_cases();
  for (const Case& c : cases)
    if (c.name == "tracer_3#0") return c;
  throw std::logic_error("no blob scene");
}

TEST(Mesher, SameBitsForAnyThreadCount) {
  const Program p = compile(*blobs().scene->objects[0].field);
  const Mesh one = mesh_case(blobs(), p, 40, 1), three = mesh_case(blobs(), p, 40, 3);
  ASSERT_GT(one.faces.size(), 0u);
  EXPECT_EQ(one.faces, three.faces);
  ASSERT_EQ(one.vertices.size(), three.vertices.size());
  for (size_t i = 0; i < one.vertices.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(one.vertices[i][a], three.vertices[i][a]);
      EXPECT_EQ(one.normals[i][a], three.normals[i][a]);
    }
}

TEST(Mesher, ARegionThatCutsTheSolidIsCapped) {
  const SceneObject& o = blobs().scene->objects[0];
  const Program p = compile(*o.field);
  Box half = o.bounds;
  half.hi.z = 0.5 * (half.lo.z + half.hi.z);
  MeshOptions opt;
  opt.cells = 40;
  const Mesh m = mesh({&p, o.iso, o.inside_sign}, half, opt);
  const mesh_check::Report r = mesh_check::check(m);
  EXPECT_EQ(r.boundary_edges + r.nonmanifold_edges + r.misoriented_edges + r.degenerate_faces, 0)
      << r.first_problem;
  long cap = 0;
  for (size_t i = 0; i < m.vertices.size(); ++i)
    if (m.vertices[i].z == m.lattice.hi.z) {
      ++cap;
      EXPECT_EQ(m.normals[i].z, 1);
    }
  EXPECT_GT(cap, 0) << "no vertex on the cut";
  EXPECT_GT(enclosed_volume(m), 0);
}

TEST(Mesher, ProgressReachesOneAndCancellationStops) {
  const Program p = compile(*blobs().scene->objects[0].field);
  const SceneObject& o = blobs().scene->objects[0];
  MeshOptions opt;
  opt.cells = 32;
  opt.threads = 2;
  std::atomic<int> calls{0};
  double last = 0;
  opt.progress = [&](double f) {
    ++calls;
    if (f == 1) last = f;
  };
  mesh({&p, o.iso, o.inside_sign}, o.bounds, opt);
  EXPECT_GT(calls, 1);
  EXPECT_EQ(last, 1);
  std::atomic<bool> cancel{true};
  opt.cancel = &cancel;
  EXPECT_THROW(mesh({&p, o.iso, o.inside_sign}, o.bounds, opt), MeshCancelled);
}

TEST(Mesher, BadRegionsAndVoxelsAreRefused) {
  const Program p = compile(*blobs().scene->objects[0].field);
  const SceneObject& o = blobs().scene->objects[0];
  MeshOptions opt;
  EXPECT_THROW(mesh({&p, o.iso, o.inside_sign}, Box::unbounded(), opt), std::invalid_argument);
  opt.voxel = -1;
  opt.cells = 0;
  EXPECT_THROW(mesh({&p, o.iso, o.inside_sign}, o.bounds, opt), std::invalid_argument);
  opt.voxel = 1e-9;
  EXPECT_THROW(mesh({&p, o.iso, o.inside_sign}, o.bounds, opt), std::invalid_argument);
}

}  // namespace
}  // namespace softtrace

// An independent check of the mesher on every scene: CGAL's polygon mesh processing (its own
// exact predicates) finds no self-intersection, builds the mesh as a closed, valid surface and
// agrees that it bounds a volume with outward faces. CGAL is compiled into this file only.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include "mesh/mesh.h"
#include "mesh_scenes.h"
#include "model/program_builder.h"

namespace softtrace {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

class MeshCgal : public ::testing::TestWithParam<mesh_scenes::Case> {};

TEST_P(MeshCgal, NoSelfIntersectionClosedAndOutward) {
  const auto& c = GetParam();
  const SceneObject& o = c.scene->objects[c.object];
  const Program p = compile(*o.field);
  MeshOptions opt;
  opt.cells = 48;
  opt.threads = 2;
  const Mesh m = mesh({&p, o.iso, o.inside_sign}, o.bounds, opt);
  ASSERT_GT(m.faces.size(), 0u);

  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(m.vertices.size());
  for (const Vec3& x : m.vertices) v.push_back(sm.add_vertex({x.x, x.y, x.z}));
  long refused = 0;
  for (const auto& f : m.faces)
    refused += sm.add_face(v[f[0]], v[f[1]], v[f[2]]) == SurfaceMesh::null_face();
  ASSERT_EQ(refused, 0) << "faces CGAL cannot add to a manifold surface";
  EXPECT_TRUE(sm.is_valid(false));
  EXPECT_TRUE(CGAL::is_closed(sm));

  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
  PMP::self_intersections(sm, std::back_inserter(pairs));
  EXPECT_EQ(pairs.size(), 0u) << "intersecting face pairs";
  EXPECT_TRUE(PMP::does_bound_a_volume(sm));
  EXPECT_TRUE(PMP::is_outward_oriented(sm));
  EXPECT_GT(PMP::volume(sm), 0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, MeshCgal, ::testing::ValuesIn(mesh_scenes::all_cases()),
                         [](const auto& info) { return mesh_scenes::test_name(info.param); });

}  // namespace
}  // namespace softtrace

// Connected components and closedness (planner/scene/mesh_components): what makes an
// obstacle or a link solid.

#include "gplanner/planner/scene/mesh_components.h"

#include <gtest/gtest.h>

namespace gplanner {
namespace {

TriangleMesh cube_at(double x, double half = 0.5) {
  return transformed(make_box(Eigen::Vector3d::Constant(2 * half)),
                     Eigen::Isometry3d(Eigen::Translation3d(x, 0, 0)));
}

// Every triangle with vertices of its own, as STL files hold them.
TriangleMesh unwelded(const TriangleMesh& mesh) {
  TriangleMesh out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const int base = static_cast<int>(out.vertices.size());
    for (int k = 0; k < 3; ++k) out.vertices.push_back(mesh.vertices[t[k]]);
    out.triangles.emplace_back(base, base + 1, base + 2);
  }
  return out;
}

TEST(MeshComponents, AClosedCubeIsOneClosedComponentWeldedOrNot) {
  for (const TriangleMesh& mesh : {cube_at(0), unwelded(cube_at(0))}) {
    const MeshComponents c = mesh_components(mesh);
    EXPECT_EQ(c.count, 1);
    EXPECT_EQ(c.open_count, 0);
    EXPECT_EQ(closed_triangles(c), std::vector<std::uint8_t>(12, 1));
  }
  for (const TriangleMesh& mesh : {make_sphere(1.0), make_cylinder(0.5, 2.0)})
    EXPECT_EQ(mesh_components(mesh).open_count, 0);
}

TEST(MeshComponents, ComponentsAreJudgedOneByOne) {
  TriangleMesh mesh = cube_at(0);
  TriangleMesh open = cube_at(3);
  open.triangles.pop_back();  // a hole: three edges without their opposite
  mesh.append(open);
  mesh.append(cube_at(6));
  const MeshComponents c = mesh_components(mesh);
  EXPECT_EQ(c.count, 3);
  EXPECT_EQ(c.open_count, 1);
  EXPECT_EQ(c.unmatched_edges, 3u);
  const std::vector<std::uint8_t> solid = closed_triangles(c);
  for (std::size_t t = 0; t < solid.size(); ++t)
    EXPECT_EQ(solid[t], t < 12 || t >= 23 ? 1 : 0) << t;
  EXPECT_EQ(describe_open_components(c).substr(0, 49),
            "1 of 3 connected components is open (3 edges with");
}

TEST(MeshComponents, ARepeatedOrFlippedTriangleOpensAComponent) {
  TriangleMesh twice = cube_at(0);
  twice.triangles.push_back(twice.triangles[0]);
  EXPECT_EQ(mesh_components(twice).open_count, 1);
  TriangleMesh flipped = cube_at(0);
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(mesh_components(flipped).open_count, 1);
  // Two cubes sharing a face (the edges of the shared face appear twice): one open
  // component when judged together.
  TriangleMesh touching = cube_at(0);
  touching.append(cube_at(1));
  const MeshComponents c = mesh_components(touching);
  EXPECT_EQ(c.count, 1);
  EXPECT_EQ(c.open_count, 1);
}

TEST(MeshComponents, LabelsKeepComponentsApart) {
  TriangleMesh touching = cube_at(0);
  touching.append(cube_at(1));
  std::vector<std::uint8_t> labels(24, 0);
  for (int t = 12; t < 24; ++t) labels[t] = 1;
  const MeshComponents c = mesh_components(touching, labels);
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.open_count, 0);
}

}  // namespace
}  // namespace gplanner

// The containment step's geometry (detail/containment.h) on answers known by
// construction: points inside and outside a closed cube, the cube mirrored (inward
// faces), points in line with its edges and vertices along every ray's direction, and
// whole bodies inside others, in float and double poses.

#include "gplanner/collision_gpu/detail/containment.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace gplanner {
namespace {

using V3d = geometry::Vec3<double>;

// A closed cube of half side h about c: 8 vertices, 12 triangles facing outward (or
// inward).
struct Cube {
  std::vector<double> vertices;
  std::vector<int> triangles;
};

Cube make_cube(V3d c, double h, bool inward = false) {
  Cube cube;
  for (int i = 0; i < 8; ++i) {
    cube.vertices.insert(cube.vertices.end(), {c.x + ((i & 1) ? h : -h), c.y + ((i & 2) ? h : -h),
                                               c.z + ((i & 4) ? h : -h)});
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    for (const int t : {1, 2}) {
      cube.triangles.insert(cube.triangles.end(),
                            {f[0], inward ? f[t + 1] : f[t], inward ? f[t] : f[t + 1]});
    }
  }
  return cube;
}

BodyComponent component(const Cube& cube, bool solid) {
  return make_body_component(cube.vertices.data(), 8, cube.triangles.data(), 12, solid);
}

TEST(Containment, PointsInAndOutOfAClosedCubeFacingEitherWay) {
  for (const bool inward : {false, true}) {
    FlatSolids solids;
    solids.add_body({component(make_cube({0, 0, 0}, 1, inward), true)});
    const SolidsView s = solids.view();
    const Component& c = s.components[0];
    ASSERT_GE(c.solid_node_offset, 0);
    for (int k = 0; k < 3; ++k) {
      const int w = detail::ray_winding(s, c, {0.1, 0.2, 0.3}, detail::containment_ray(k));
      EXPECT_EQ(w, inward ? -1 : 1) << "ray " << k;
      EXPECT_EQ(detail::ray_winding(s, c, {3, 0.2, 0.3}, detail::containment_ray(k)), 0);
    }
    // Points on a grid, many of them in the planes of the cube's faces' diagonals and
    // in line with its edges, inside by a little or outside by a little.
    for (double x = -1.5; x <= 1.5; x += 0.25) {
      for (double y = -1.5; y <= 1.5; y += 0.25) {
        for (double z = -1.5; z <= 1.5; z += 0.25) {
          const double m = std::max({std::abs(x), std::abs(y), std::abs(z)});
          if (std::abs(m - 1) < 1e-9) continue;  // on the surface: never asked
          EXPECT_EQ(detail::point_in_solid(s, c, {x, y, z}), m < 1)
              << x << " " << y << " " << z << (inward ? " inward" : "");
        }
      }
    }
  }
}

// A point placed so that one ray passes exactly through a vertex of the cube: the other
// two rays outvote it.
TEST(Containment, ARayThroughAVertexIsOutvoted) {
  FlatSolids solids;
  solids.add_body({component(make_cube({0, 0, 0}, 1), true)});
  const SolidsView s = solids.view();
  const V3d corner{1, 1, 1};
  for (int k = 0; k < 3; ++k) {
    const V3d d = detail::containment_ray(k);
    for (const double t : {0.5, 3.0}) {  // inside and outside along the ray to the corner
      const V3d p = corner - t * d;
      const bool inside = std::abs(p.x) < 1 && std::abs(p.y) < 1 && std::abs(p.z) < 1;
      EXPECT_EQ(detail::point_in_solid(s, s.components[0], p), inside) << "ray " << k << " " << t;
    }
  }
}

TEST(Containment, BodiesInsideOthersEachWayAndApart) {
  // Body A: a small cube (solid); body B: a large cube (solid) and an open surface
  // piece (two triangles of another cube's face) far away.
  const Cube small = make_cube({0, 0, 0}, 0.1), large = make_cube({0, 0, 0}, 1);
  FlatSolids solids;
  const BodySolids a = solids.add_body({component(small, true)});
  Cube piece = make_cube({10, 0, 0}, 0.1);
  piece.triangles.resize(6);
  const BodySolids b = solids.add_body(
      {component(large, true),
       make_body_component(piece.vertices.data(), 8, piece.triangles.data(), 2, false)});
  EXPECT_GE(b.points, 0);
  EXPECT_GE(b.solids, 0);
  const SolidsView s = solids.view();
  const auto place = [](double x, double y, double z, double angle) {
    geometry::Transform<double> X;
    X.R = geometry::axis_angle(V3d{0.6, 0.8, 0}, angle);
    X.t = {x, y, z};
    return X;
  };
  const double margin = 1e-4;
  // A (placed in B by X_BA) inside B's large cube; the other way round nothing.
  EXPECT_TRUE(detail::components_inside(s, a, b, place(0.5, -0.3, 0.2, 0.7), margin));
  EXPECT_FALSE(detail::components_inside(s, b, a, place(0.5, -0.3, 0.2, 0.7), margin));
  EXPECT_TRUE(detail::either_inside(s, b, a, place(0.5, -0.3, 0.2, 0.7), margin));
  EXPECT_TRUE(
      detail::either_inside(s, a, b, geometry::inverse(place(0.5, -0.3, 0.2, 0.7)), margin));
  // Outside it, and inside the open piece's box: nothing.
  EXPECT_FALSE(detail::either_inside(s, b, a, place(3, 0, 0, 0.7), margin));
  EXPECT_FALSE(detail::either_inside(s, b, a, place(10, 0, 0, 0), margin));
  // The same in float poses.
  geometry::Transform<float> X_f;
  const geometry::Transform<double> X_d = place(-0.6, 0.4, 0.5, 2.0);
  for (int i = 0; i < 3; ++i) {
    X_f.R.r[i] = {float(X_d.R.r[i].x), float(X_d.R.r[i].y), float(X_d.R.r[i].z)};
  }
  X_f.t = {float(X_d.t.x), float(X_d.t.y), float(X_d.t.z)};
  EXPECT_TRUE(detail::either_inside(s, b, a, X_f, 1e-4f));
}

// Many small solid cubes (components of one body) against a body of one point: the
// trees find exactly the cube the point is in, whichever it is.
TEST(Containment, TheTreesFindTheOneComponentThatHolds) {
  std::vector<BodyComponent> cubes;
  std::vector<Cube> kept;
  for (int i = 0; i < 64; ++i) {
    kept.push_back(make_cube({double(i % 4), double(i / 4 % 4), double(i / 16)}, 0.3));
    cubes.push_back(component(kept.back(), true));
  }
  FlatSolids solids;
  const BodySolids many = solids.add_body(cubes);
  const BodySolids tiny = solids.add_body({component(make_cube({0, 0, 0}, 0.01), false)});
  const SolidsView s = solids.view();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-0.5, 3.5);
  int inside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    geometry::Transform<double> X = geometry::identity_transform<double>();
    X.t = {coordinate(random), coordinate(random), coordinate(random)};
    // The tiny cube's point is its vertex (-0.01, -0.01, -0.01).
    const V3d p = X.t - V3d{0.01, 0.01, 0.01};
    bool expected = false;
    for (int i = 0; i < 64; ++i) {
      const V3d c{double(i % 4), double(i / 4 % 4), double(i / 16)};
      expected = expected || (std::abs(p.x - c.x) < 0.3 && std::abs(p.y - c.y) < 0.3 &&
                              std::abs(p.z - c.z) < 0.3);
    }
    inside += expected;
    EXPECT_EQ(detail::components_inside(s, tiny, many, X, 1e-6), expected) << trial;
  }
  EXPECT_GT(inside, 100);
  // A component larger than every solid cube fits in none: its subtree is skipped.
  FlatSolids more;
  const BodySolids cubes_again = more.add_body(cubes);
  const BodySolids big = more.add_body({component(make_cube({0, 0, 0}, 2), false)});
  geometry::Transform<double> X = geometry::identity_transform<double>();
  X.t = {2.01, 2.01, 2.01};  // its point (a vertex) at (0.01, 0.01, 0.01): in cube 0's box
  EXPECT_FALSE(detail::components_inside(more.view(), big, cubes_again, X, 1e-6));
}

}  // namespace
}  // namespace gplanner

#pragma once
// An indexed triangle mesh in double precision, the form every robot link and obstacle
// takes once loaded, and the tessellation of URDF / scene primitives.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace gplanner {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // vertex indices, counter-clockwise outside

  std::size_t triangle_count() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }

  // Appends `other` with its vertices mapped by X_this_other.
  void append(const TriangleMesh& other,
              const Eigen::Isometry3d& X_this_other = Eigen::Isometry3d::Identity());

  // Axis-aligned bounds of the vertices (empty box when there are none).
  Eigen::AlignedBox3d bounds() const;
};

// A copy with every vertex mapped by X_BA (the mesh given in frame A, returned in B).
TriangleMesh transformed(const TriangleMesh& mesh_A, const Eigen::Isometry3d& X_BA);

// Primitives, centred at the origin. Curved ones are tessellated so that the polyhedron
// contains the exact shape (vertices pushed out), keeping collision checks conservative.
TriangleMesh make_box(const Eigen::Vector3d& size);  // full side lengths
TriangleMesh make_sphere(double radius, int rings = 12, int segments = 24);
TriangleMesh make_cylinder(double radius, double length, int segments = 24);  // axis z

// How far the faces of make_sphere and make_cylinder lie outside the exact shape at most
// (at their vertices).
double sphere_tessellation_excess(double radius, int rings, int segments);
double cylinder_tessellation_excess(double radius, int segments);

}  // namespace gplanner

#include "gplanner/planner/scene/triangle_mesh.h"

#include <cmath>

namespace gplanner {

void TriangleMesh::append(const TriangleMesh& other, const Eigen::Isometry3d& X_this_other) {
  const int base = static_cast<int>(vertices.size());
  vertices.reserve(vertices.size() + other.vertices.size());
  for (const Eigen::Vector3d& p : other.vertices) vertices.push_back(X_this_other * p);
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const Eigen::Vector3i& t : other.triangles) triangles.push_back(t.array() + base);
}

Eigen::AlignedBox3d TriangleMesh::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : vertices) box.extend(p);
  return box;
}

TriangleMesh transformed(const TriangleMesh& mesh_A, const Eigen::Isometry3d& X_BA) {
  TriangleMesh mesh_B;
  mesh_B.append(mesh_A, X_BA);
  return mesh_B;
}

TriangleMesh make_box(const Eigen::Vector3d& size) {
  TriangleMesh mesh;
  const Eigen::Vector3d h = size / 2;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                               (i & 4) ? h.z() : -h.z());
  }
  // Two triangles per face, counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return mesh;
}

TriangleMesh make_sphere(double radius, int rings, int segments) {
  // A UV sphere whose faces all lie outside the exact sphere: the ring radius and the
  // poles are scaled so that the plane of every face clears the sphere.
  const double kPi = std::acos(-1.0);
  const double r = radius / (std::cos(kPi / segments) * std::cos(kPi / (2 * rings)));
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0, 0, -r);
  for (int i = 1; i < rings; ++i) {
    const double phi = -kPi / 2 + kPi * i / rings;
    for (int s = 0; s < segments; ++s) {
      const double theta = 2 * kPi * s / segments;
      mesh.vertices.emplace_back(r * std::cos(phi) * std::cos(theta),
                                 r * std::cos(phi) * std::sin(theta), r * std::sin(phi));
    }
  }
  mesh.vertices.emplace_back(0, 0, r);
  const int top = static_cast<int>(mesh.vertices.size()) - 1;
  const int last_ring = 1 + (rings - 2) * segments;
  for (int s = 0; s < segments; ++s) {
    const int n = (s + 1) % segments;
    mesh.triangles.emplace_back(0, 1 + n, 1 + s);
    mesh.triangles.emplace_back(top, last_ring + s, last_ring + n);
    for (int i = 0; i + 2 < rings; ++i) {
      const int a = 1 + i * segments + s, b = 1 + i * segments + n;
      mesh.triangles.emplace_back(a, b, b + segments);
      mesh.triangles.emplace_back(a, b + segments, a + segments);
    }
  }
  return mesh;
}

TriangleMesh make_cylinder(double radius, double length, int segments) {
  const double kPi = std::acos(-1.0);
  const double r = radius / std::cos(kPi / segments);  // circumscribed polygon
  TriangleMesh mesh;
  for (const double z : {-length / 2, length / 2}) {
    for (int s = 0; s < segments; ++s) {
      const double theta = 2 * kPi * s / segments;
      mesh.vertices.emplace_back(r * std::cos(theta), r * std::sin(theta), z);
    }
  }
  mesh.vertices.emplace_back(0, 0, -length / 2);
  mesh.vertices.emplace_back(0, 0, length / 2);
  const int bottom = 2 * segments, top = 2 * segments + 1;
  for (int s = 0; s < segments; ++s) {
    const int n = (s + 1) % segments;
    mesh.triangles.emplace_back(s, n, segments + n);
    mesh.triangles.emplace_back(s, segments + n, segments + s);
    mesh.triangles.emplace_back(bottom, n, s);
    mesh.triangles.emplace_back(top, segments + s, segments + n);
  }
  return mesh;
}

double sphere_tessellation_excess(double radius, int rings, int segments) {
  const double kPi = std::acos(-1.0);
  return radius * (1 / (std::cos(kPi / segments) * std::cos(kPi / (2 * rings))) - 1);
}

double cylinder_tessellation_excess(double radius, int segments) {
  const double kPi = std::acos(-1.0);
  return radius * (1 / std::cos(kPi / segments) - 1);
}

}  // namespace gplanner

#pragma once
// The connected components of a triangle mesh and which of them are closed: what decides
// whether an obstacle or a link is solid (docs/design.md, "Solids"; docs/scenes.md).

#include <cstdint>
#include <string>
#include <vector>

#include "gplanner/planner/scene/triangle_mesh.h"

namespace gplanner {

struct MeshComponents {
  std::vector<int> of_triangle;      // the component of each triangle
  int count = 0;                     // components
  std::vector<std::uint8_t> closed;  // per component
  int open_count = 0;                // components not closed
  std::size_t unmatched_edges = 0;   // directed edges of open components without exactly
                                     // one opposite, or appearing more than once
  Eigen::Vector3d open_edge_from = Eigen::Vector3d::Zero();  // one such edge
  Eigen::Vector3d open_edge_to = Eigen::Vector3d::Zero();
};

// Vertices are welded by exact position; triangles sharing a welded vertex, and the
// same label (labels: 0 or 1 per triangle, or empty for all alike), belong to one
// component. A component is closed when every directed edge (a, b) of its triangles
// appears once and its opposite (b, a) once: a watertight, consistently oriented
// surface. Triangles with two corners at one position carry no area and are left out of
// that count; a component of nothing else is open.
MeshComponents mesh_components(const TriangleMesh& mesh,
                               const std::vector<std::uint8_t>& labels = {});

// Per triangle: 1 where its component is closed (a solid), 0 where open (a surface).
std::vector<std::uint8_t> closed_triangles(const MeshComponents& components);

// "N of M connected components are open (K unmatched edges, e.g. the edge from (x, y, z)
// to (x, y, z))": what a notice or error says of a mesh that is not closed.
std::string describe_open_components(const MeshComponents& components);

}  // namespace gplanner

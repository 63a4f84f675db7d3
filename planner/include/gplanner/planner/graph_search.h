#pragma once
// A* over a roadmap's edges, skipping invalid ones (and, when asked, unknown ones), with
// the metric distance to the goal as the heuristic (admissible: an edge's length is
// the metric distance between its ends).

#include <cstdint>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/roadmap.h"

namespace gplanner {

struct GraphPath {
  std::vector<std::uint32_t> vertices;  // start ... goal; empty when none exists
  std::vector<std::uint32_t> edges;     // edges[i] joins vertices[i] and vertices[i + 1]
  double length = 0;
};

GraphPath shortest_path(const Roadmap& roadmap, const ConfigurationMetric& metric,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only);

}  // namespace gplanner

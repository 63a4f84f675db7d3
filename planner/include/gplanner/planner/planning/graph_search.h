#pragma once
// A* over a roadmap's edges, skipping invalid ones (and, when asked, unknown ones). The
// heuristic is either the metric distance to the goal (admissible: an edge's length is
// the metric distance between its ends) or a cost to the goal computed over the roadmap
// itself (GoalDistances), which stays a lower bound while edges only become invalid and
// lets a lazy search go straight to the next best path instead of searching the whole
// roadmap again.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/planning/roadmap.h"

namespace gplanner {

struct GraphPath {
  std::vector<std::uint32_t> vertices;  // start ... goal; empty when none exists
  std::vector<std::uint32_t> edges;     // edges[i] joins vertices[i] and vertices[i + 1]
  double length = 0;
  std::size_t expanded = 0;  // vertices the search expanded
  bool gave_up = false;      // stopped after max_expanded expansions (vertices empty)
};

GraphPath shortest_path(const Roadmap& roadmap, const ConfigurationMetric& metric,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only);

// to_goal[v]: a lower bound on v's cost to the goal over the usable edges, consistent
// (to_goal[v] <= length(v, w) + to_goal[w] for every usable edge), infinity where v
// cannot reach the goal; shape [roadmap.vertex_count()].
// Gives up (an empty path, gave_up set) once it has expanded max_expanded vertices, or
// when `should_stop` (polled every few thousand expansions) says to.
GraphPath shortest_path(const Roadmap& roadmap, const std::vector<double>& to_goal,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only,
                        std::size_t max_expanded = ~std::size_t(0),
                        const std::function<bool()>& should_stop = {});

}  // namespace gplanner

#include "gplanner/planner/planning/graph_search.h"

#include "a_star.h"

namespace gplanner {
namespace {

// A roadmap's usable edges at v, in its order.
auto roadmap_edges(const Roadmap& roadmap, bool valid_edges_only) {
  return [&roadmap, valid_edges_only](std::uint32_t v, const auto& visit) {
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (usable(edge, valid_edges_only)) visit(e, edge.a == v ? edge.b : edge.a, edge.length);
    }
  };
}

}  // namespace

GraphPath shortest_path(const Roadmap& roadmap, const ConfigurationMetric& metric,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only) {
  const float* q_goal = roadmap.vertex(goal);
  return detail::a_star(
      roadmap.vertex_count(), start, goal, roadmap_edges(roadmap, valid_edges_only),
      [&](std::uint32_t v) {
        return static_cast<double>(configuration_distance(metric, roadmap.vertex(v), q_goal));
      },
      ~std::size_t(0), {});
}

GraphPath shortest_path(const Roadmap& roadmap, const std::vector<double>& to_goal,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only,
                        std::size_t max_expanded, const std::function<bool()>& should_stop) {
  return detail::a_star(
      roadmap.vertex_count(), start, goal, roadmap_edges(roadmap, valid_edges_only),
      [&](std::uint32_t v) { return to_goal[v]; }, max_expanded, should_stop);
}

}  // namespace gplanner

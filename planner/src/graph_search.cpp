#include "gplanner/planner/graph_search.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace gplanner {

GraphPath shortest_path(const Roadmap& roadmap, const ConfigurationMetric& metric,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only) {
  const std::size_t n = roadmap.vertex_count();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> cost(n, kInf);
  std::vector<std::uint32_t> via_edge(n, ~0u);
  std::vector<bool> closed(n, false);
  using Entry = std::pair<double, std::uint32_t>;  // (cost + heuristic, vertex)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const float* q_goal = roadmap.vertex(goal);
  auto heuristic = [&](std::uint32_t v) {
    return static_cast<double>(configuration_distance(metric, roadmap.vertex(v), q_goal));
  };
  cost[start] = 0;
  open.emplace(heuristic(start), start);
  while (!open.empty()) {
    const std::uint32_t v = open.top().second;
    open.pop();
    if (closed[v]) continue;
    closed[v] = true;
    if (v == goal) break;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (edge.state == EdgeState::kInvalid) continue;
      if (valid_edges_only && edge.state != EdgeState::kValid) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      const double c = cost[v] + edge.length;
      if (c < cost[w]) {
        cost[w] = c;
        via_edge[w] = e;
        open.emplace(c + heuristic(w), w);
      }
    }
  }
  GraphPath path;
  if (!closed[goal]) return path;
  path.length = cost[goal];
  for (std::uint32_t v = goal; v != start;) {
    const RoadmapEdge& edge = roadmap.edge(via_edge[v]);
    path.vertices.push_back(v);
    path.edges.push_back(via_edge[v]);
    v = edge.a == v ? edge.b : edge.a;
  }
  path.vertices.push_back(start);
  std::reverse(path.vertices.begin(), path.vertices.end());
  std::reverse(path.edges.begin(), path.edges.end());
  return path;
}

}  // namespace gplanner

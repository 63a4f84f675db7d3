#include "gplanner/planner/graph_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

namespace gplanner {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool usable(const RoadmapEdge& edge, bool valid_edges_only) {
  if (edge.state == EdgeState::kInvalid) return false;
  return !valid_edges_only || edge.state == EdgeState::kValid;
}

// A* from start to goal; `heuristic(v)` a consistent lower bound on v's cost to the goal
// (infinity: v cannot reach it, and is not expanded).
template <class Heuristic>
GraphPath a_star(const Roadmap& roadmap, std::uint32_t start, std::uint32_t goal,
                 bool valid_edges_only, const Heuristic& heuristic) {
  const std::size_t n = roadmap.vertex_count();
  std::vector<double> cost(n, kInf);
  std::vector<std::uint32_t> via_edge(n, ~0u);
  std::vector<bool> closed(n, false);
  using Entry = std::pair<double, std::uint32_t>;  // (cost + heuristic, vertex)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  GraphPath path;
  const double h_start = heuristic(start);
  if (std::isinf(h_start)) return path;
  cost[start] = 0;
  open.emplace(h_start, start);
  while (!open.empty()) {
    const std::uint32_t v = open.top().second;
    open.pop();
    if (closed[v]) continue;
    closed[v] = true;
    ++path.expanded;
    if (v == goal) break;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (!usable(edge, valid_edges_only)) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      const double c = cost[v] + edge.length;
      if (c < cost[w]) {
        const double h = heuristic(w);
        if (std::isinf(h)) continue;
        cost[w] = c;
        via_edge[w] = e;
        open.emplace(c + h, w);
      }
    }
  }
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

}  // namespace

GraphPath shortest_path(const Roadmap& roadmap, const ConfigurationMetric& metric,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only) {
  const float* q_goal = roadmap.vertex(goal);
  return a_star(roadmap, start, goal, valid_edges_only, [&](std::uint32_t v) {
    return static_cast<double>(configuration_distance(metric, roadmap.vertex(v), q_goal));
  });
}

GraphPath shortest_path(const Roadmap& roadmap, const std::vector<double>& to_goal,
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only) {
  return a_star(roadmap, start, goal, valid_edges_only,
                [&](std::uint32_t v) { return to_goal[v]; });
}

std::vector<double> cost_to_goal(const Roadmap& roadmap, std::uint32_t goal,
                                 bool valid_edges_only) {
  std::vector<double> cost(roadmap.vertex_count(), kInf);
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[goal] = 0;
  open.emplace(0, goal);
  while (!open.empty()) {
    const auto [c, v] = open.top();
    open.pop();
    if (c > cost[v]) continue;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (!usable(edge, valid_edges_only)) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      if (c + edge.length < cost[w]) {
        cost[w] = c + edge.length;
        open.emplace(cost[w], w);
      }
    }
  }
  return cost;
}

}  // namespace gplanner

#include "gplanner/planner/planning/graph_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

namespace gplanner {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Per-thread arrays of the last search, reused so that a search costs what it expands,
// not the roadmap's size (lazy PRM searches a roadmap of 10^5 vertices hundreds of
// times). An entry belongs to the current search when its stamp is the search's.
struct SearchScratch {
  std::vector<double> cost;
  std::vector<std::uint32_t> via_edge;
  std::vector<std::uint32_t> reached, closed;  // stamps
  std::uint32_t stamp = 0;

  void begin(std::size_t n) {
    if (reached.size() < n) {
      cost.resize(n);
      via_edge.resize(n);
      reached.resize(n, 0);
      closed.resize(n, 0);
    }
    if (++stamp == 0) {  // wrapped: forget every old stamp
      std::fill(reached.begin(), reached.end(), 0);
      std::fill(closed.begin(), closed.end(), 0);
      stamp = 1;
    }
  }
  double cost_of(std::uint32_t v) const { return reached[v] == stamp ? cost[v] : kInf; }
  bool is_closed(std::uint32_t v) const { return closed[v] == stamp; }
};

// A* from start to goal; `heuristic(v)` a consistent lower bound on v's cost to the goal
// (infinity: v cannot reach it, and is not expanded).
template <class Heuristic>
GraphPath a_star(const Roadmap& roadmap, std::uint32_t start, std::uint32_t goal,
                 bool valid_edges_only, const Heuristic& heuristic,
                 std::size_t max_expanded = ~std::size_t(0),
                 const std::function<bool()>& should_stop = {}) {
  constexpr std::size_t kStopPoll = 4096;
  thread_local SearchScratch scratch;
  scratch.begin(roadmap.vertex_count());
  using Entry = std::pair<double, std::uint32_t>;  // (cost + heuristic, vertex)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  GraphPath path;
  const double h_start = heuristic(start);
  if (std::isinf(h_start)) return path;
  scratch.cost[start] = 0;
  scratch.reached[start] = scratch.stamp;
  open.emplace(h_start, start);
  while (!open.empty()) {
    const std::uint32_t v = open.top().second;
    open.pop();
    if (scratch.is_closed(v)) continue;
    scratch.closed[v] = scratch.stamp;
    ++path.expanded;
    if (v == goal) break;
    if (path.expanded >= max_expanded ||
        (path.expanded % kStopPoll == 0 && should_stop && should_stop())) {
      path.gave_up = true;
      return path;
    }
    const double cost_v = scratch.cost[v];
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (!usable(edge, valid_edges_only)) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      const double c = cost_v + edge.length;
      if (c < scratch.cost_of(w)) {
        const double h = heuristic(w);
        if (std::isinf(h)) continue;
        scratch.cost[w] = c;
        scratch.reached[w] = scratch.stamp;
        scratch.via_edge[w] = e;
        open.emplace(c + h, w);
      }
    }
  }
  if (!scratch.is_closed(goal)) return path;
  path.length = scratch.cost[goal];
  for (std::uint32_t v = goal; v != start;) {
    const std::uint32_t e = scratch.via_edge[v];
    const RoadmapEdge& edge = roadmap.edge(e);
    path.vertices.push_back(v);
    path.edges.push_back(e);
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
                        std::uint32_t start, std::uint32_t goal, bool valid_edges_only,
                        std::size_t max_expanded, const std::function<bool()>& should_stop) {
  return a_star(
      roadmap, start, goal, valid_edges_only, [&](std::uint32_t v) { return to_goal[v]; },
      max_expanded, should_stop);
}

}  // namespace gplanner

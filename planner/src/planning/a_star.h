#pragma once
// A* from a start to a goal vertex, over edges that the caller lists: shared by
// graph_search.cpp (a roadmap's edge lists) and GoalDistances (its rows of the same
// edges, read in one run). Both list a vertex's edges in the same order, so that they
// expand, and break ties, alike.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "gplanner/planner/planning/graph_search.h"

namespace gplanner {
namespace detail {

// Per-thread arrays of the last search, reused so that a search costs what it expands,
// not the roadmap's size (lazy PRM searches a roadmap of 10^5 vertices hundreds of
// times). An entry belongs to the current search when its stamp is the search's.
struct SearchScratch {
  std::vector<double> cost;
  std::vector<std::uint32_t> via_edge, via_vertex;
  std::vector<std::uint32_t> reached, closed;  // stamps
  std::uint32_t stamp = 0;

  void begin(std::size_t n) {
    if (reached.size() < n) {
      cost.resize(n);
      via_edge.resize(n);
      via_vertex.resize(n);
      reached.resize(n, 0);
      closed.resize(n, 0);
    }
    if (++stamp == 0) {  // wrapped: forget every old stamp
      std::fill(reached.begin(), reached.end(), 0);
      std::fill(closed.begin(), closed.end(), 0);
      stamp = 1;
    }
  }
  double cost_of(std::uint32_t v) const {
    return reached[v] == stamp ? cost[v] : std::numeric_limits<double>::infinity();
  }
  bool is_closed(std::uint32_t v) const { return closed[v] == stamp; }
};

// The calling thread's scratch (one per thread for the whole program).
inline SearchScratch& search_scratch() {
  thread_local SearchScratch scratch;
  return scratch;
}

// A* from start to goal over `vertices` vertices. for_each_edge(v, f) calls
// f(edge, w, length) for each usable edge from v to w; heuristic(v) is a consistent lower
// bound on v's cost to the goal (infinity: v cannot reach it, and is not expanded). Gives
// up (gave_up set, no path) after max_expanded expansions or when should_stop (polled
// every few thousand) says so.
template <class ForEachEdge, class Heuristic>
GraphPath a_star(std::size_t vertices, std::uint32_t start, std::uint32_t goal,
                 const ForEachEdge& for_each_edge, const Heuristic& heuristic,
                 std::size_t max_expanded, const std::function<bool()>& should_stop) {
  constexpr std::size_t kStopPoll = 4096;
  SearchScratch& scratch = search_scratch();
  scratch.begin(vertices);
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
    for_each_edge(v, [&](std::uint32_t e, std::uint32_t w, float length) {
      const double c = cost_v + length;
      if (c < scratch.cost_of(w)) {
        const double h = heuristic(w);
        if (std::isinf(h)) return;
        scratch.cost[w] = c;
        scratch.reached[w] = scratch.stamp;
        scratch.via_edge[w] = e;
        scratch.via_vertex[w] = v;
        open.emplace(c + h, w);
      }
    });
  }
  if (!scratch.is_closed(goal)) return path;
  path.length = scratch.cost[goal];
  for (std::uint32_t v = goal; v != start; v = scratch.via_vertex[v]) {
    path.vertices.push_back(v);
    path.edges.push_back(scratch.via_edge[v]);
  }
  path.vertices.push_back(start);
  std::reverse(path.vertices.begin(), path.vertices.end());
  std::reverse(path.edges.begin(), path.edges.end());
  return path;
}

}  // namespace detail
}  // namespace gplanner

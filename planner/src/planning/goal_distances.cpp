#include "gplanner/planner/planning/goal_distances.h"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace gplanner {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = ~std::uint32_t(0);

using Entry = std::pair<double, std::uint32_t>;  // (cost, vertex)
using MinQueue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;

// Dijkstra from the queued vertices outwards over the usable edges: each vertex is
// settled at its least cost, and its edges lower their other ends' costs. (After
// remove_edges seeds it, only the affected vertices can be lowered: the others keep the
// costs of ways that still exist.) Polls `should_stop` every kStopPoll vertices; false
// when it said to stop, the costs then unfinished.
bool settle(const Roadmap& roadmap, bool valid_edges_only, const std::function<bool()>& should_stop,
            MinQueue* open, std::vector<double>* cost, std::vector<std::uint32_t>* via) {
  constexpr std::size_t kStopPoll = 4096;
  for (std::size_t popped = 1; !open->empty(); ++popped) {
    if (popped % kStopPoll == 0 && should_stop && should_stop()) return false;
    const auto [c, v] = open->top();
    open->pop();
    if (c > (*cost)[v]) continue;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (!usable(edge, valid_edges_only)) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      if (c + edge.length < (*cost)[w]) {
        (*cost)[w] = c + edge.length;
        (*via)[w] = e;
        open->emplace((*cost)[w], w);
      }
    }
  }
  return true;
}

}  // namespace

void GoalDistances::compute(const Roadmap& roadmap, std::uint32_t goal, bool valid_edges_only) {
  valid_edges_only_ = valid_edges_only;
  goal_ = goal;
  cost_.assign(roadmap.vertex_count(), kInf);
  via_.assign(roadmap.vertex_count(), kNone);
  affected_.assign(roadmap.vertex_count(), 0);
  MinQueue open;
  cost_[goal] = 0;
  open.emplace(0, goal);
  stopped_ = !settle(roadmap, valid_edges_only_, should_stop_, &open, &cost_, &via_);
}

std::size_t GoalDistances::remove_edges(const Roadmap& roadmap,
                                        const std::vector<std::uint32_t>& edges,
                                        std::size_t max_affected) {
  // The affected vertices: those whose first edge to the goal was removed, and then
  // every vertex whose way goes through an affected one (the tree of ways below them,
  // found through each affected vertex's edges: w hangs below v when w's first edge is
  // the edge from v).
  affected_.resize(cost_.size(), 0);  // all 0 between calls
  std::vector<std::uint32_t>& found = found_;
  found.clear();
  for (const std::uint32_t e : edges) {
    const RoadmapEdge& edge = roadmap.edge(e);
    if (usable(edge, valid_edges_only_)) continue;
    for (const std::uint32_t v : {edge.a, edge.b}) {
      if (via_[v] == e && !affected_[v]) {
        affected_[v] = 1;
        found.push_back(v);
      }
    }
  }
  // Past half of all vertices, a Dijkstra from the goal over all costs less than
  // repairing them (finding them, then seeding each from its neighbours): on lazy PRM's
  // roadmaps an invalid edge near the goal leaves most of the roadmap affected.
  const std::size_t most = cost_.size() / 2;
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (found.size() > std::min(max_affected, most)) {
      for (const std::uint32_t u : found) affected_[u] = 0;
      if (found.size() > max_affected) return max_affected + 1;
      compute(roadmap, goal_, valid_edges_only_);
      return cost_.size();
    }
    const std::uint32_t v = found[i];
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      if (via_[w] == e && !affected_[w]) {
        affected_[w] = 1;
        found.push_back(w);
      }
    }
  }
  // They start from their best neighbour whose cost holds, then settle among themselves
  // in cost order.
  MinQueue open;
  for (const std::uint32_t v : found) {
    cost_[v] = kInf;
    via_[v] = kNone;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (!usable(edge, valid_edges_only_)) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      if (affected_[w]) continue;
      if (cost_[w] + edge.length < cost_[v]) {
        cost_[v] = cost_[w] + edge.length;
        via_[v] = e;
      }
    }
    if (via_[v] != kNone) open.emplace(cost_[v], v);
  }
  stopped_ = !settle(roadmap, valid_edges_only_, should_stop_, &open, &cost_, &via_);
  for (const std::uint32_t v : found) affected_[v] = 0;
  return found.size();
}

}  // namespace gplanner

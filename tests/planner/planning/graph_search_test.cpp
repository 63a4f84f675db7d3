// A* over roadmaps against Dijkstra (no heuristic) on random geometric graphs, with the
// metric heuristic and with a cost to the goal computed before edges became invalid.

#include "gplanner/planner/planning/graph_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include "gplanner/planner/planning/goal_distances.h"

namespace gplanner {
namespace {

double dijkstra(const Roadmap& roadmap, std::uint32_t s, std::uint32_t g, bool valid_only) {
  std::vector<double> cost(roadmap.vertex_count(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[s] = 0;
  open.emplace(0, s);
  while (!open.empty()) {
    const auto [c, v] = open.top();
    open.pop();
    if (c > cost[v]) continue;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (edge.state == EdgeState::kInvalid) continue;
      if (valid_only && edge.state != EdgeState::kValid) continue;
      const std::uint32_t w = edge.a == v ? edge.b : edge.a;
      if (c + edge.length < cost[w]) {
        cost[w] = c + edge.length;
        open.emplace(cost[w], w);
      }
    }
  }
  return cost[g];
}

// A random geometric roadmap of `vertices` vertices and 4 times as many edges in each state.
Roadmap random_roadmap(const ConfigurationMetric& metric, std::mt19937* rng,
                       std::uint32_t vertices = 200) {
  std::uniform_real_distribution<float> coord(0, 10);
  Roadmap roadmap(2);
  for (std::uint32_t i = 0; i < vertices; ++i) {
    const float q[] = {coord(*rng), coord(*rng)};
    roadmap.add_vertex(q);
  }
  std::uniform_int_distribution<std::uint32_t> pick(0, vertices - 1);
  std::uniform_int_distribution<int> state(0, 2);
  for (std::uint32_t e = 0; e < 4 * vertices; ++e) {
    const std::uint32_t a = pick(*rng), b = pick(*rng);
    roadmap.add_edge(a, b, configuration_distance(metric, roadmap.vertex(a), roadmap.vertex(b)),
                     static_cast<EdgeState>(state(*rng)));
  }
  return roadmap;
}

// The path is one of `roadmap` from 0 to 1 over usable edges, of length `expected`.
void expect_shortest(const Roadmap& roadmap, const GraphPath& path, double expected,
                     bool valid_only) {
  if (std::isinf(expected)) {
    EXPECT_TRUE(path.vertices.empty());
    return;
  }
  ASSERT_FALSE(path.vertices.empty());
  EXPECT_NEAR(path.length, expected, 1e-4 * expected);
  EXPECT_EQ(path.vertices.front(), 0u);
  EXPECT_EQ(path.vertices.back(), 1u);
  ASSERT_EQ(path.edges.size() + 1, path.vertices.size());
  double sum = 0;
  for (std::size_t i = 0; i < path.edges.size(); ++i) {
    const RoadmapEdge& e = roadmap.edge(path.edges[i]);
    EXPECT_NE(e.state, EdgeState::kInvalid);
    if (valid_only) EXPECT_EQ(e.state, EdgeState::kValid);
    EXPECT_TRUE((e.a == path.vertices[i] && e.b == path.vertices[i + 1]) ||
                (e.b == path.vertices[i] && e.a == path.vertices[i + 1]));
    sum += e.length;
  }
  EXPECT_NEAR(sum, path.length, 1e-4 * expected);
}

TEST(GraphSearch, FindsTheShortestPathOverUsableEdges) {
  ConfigurationMetric metric;  // joints only: 2 of them
  metric.joint_count = 2;
  std::mt19937 rng(8);
  for (int trial = 0; trial < 20; ++trial) {
    const Roadmap roadmap = random_roadmap(metric, &rng);
    for (const bool valid_only : {false, true}) {
      expect_shortest(roadmap, shortest_path(roadmap, metric, 0, 1, valid_only),
                      dijkstra(roadmap, 0, 1, valid_only), valid_only);
    }
  }
}

// Searches reuse their arrays from one call to the next: roadmaps of changing sizes,
// searched in turn, still give Dijkstra's lengths.
TEST(GraphSearch, SearchesOfRoadmapsOfChangingSizesStayExact) {
  ConfigurationMetric metric;
  metric.joint_count = 2;
  std::mt19937 rng(10);
  for (const std::uint32_t size : {50u, 2000u, 200u, 7u, 1000u}) {
    const Roadmap roadmap = random_roadmap(metric, &rng, size);
    for (const bool valid_only : {false, true}) {
      GoalDistances distances;
      distances.compute(roadmap, 1, valid_only);
      const std::vector<double>& to_goal = distances.cost();
      const double expected = dijkstra(roadmap, 0, 1, valid_only);
      expect_shortest(roadmap, shortest_path(roadmap, metric, 0, 1, valid_only), expected,
                      valid_only);
      expect_shortest(roadmap, shortest_path(roadmap, to_goal, 0, 1, valid_only), expected,
                      valid_only);
    }
  }
}

// A search bounded by max_expanded gives up (an empty path, gave_up) when it would need
// more, and finds the same path when it needs no more.
TEST(GraphSearch, GivesUpAfterMaxExpanded) {
  ConfigurationMetric metric;
  metric.joint_count = 2;
  std::mt19937 rng(11);
  int gave_up = 0, found = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Roadmap roadmap = random_roadmap(metric, &rng);
    // A heuristic that guides nothing: the search expands much of the roadmap.
    const std::vector<double> zero(roadmap.vertex_count(), 0.0);
    const GraphPath full = shortest_path(roadmap, zero, 0, 1, false);
    EXPECT_FALSE(full.gave_up);
    if (full.vertices.empty() || full.expanded < 3) continue;
    const GraphPath cut = shortest_path(roadmap, zero, 0, 1, false, full.expanded - 1);
    EXPECT_TRUE(cut.gave_up);
    EXPECT_TRUE(cut.vertices.empty());
    EXPECT_EQ(cut.expanded, full.expanded - 1);
    ++gave_up;
    const GraphPath enough = shortest_path(roadmap, zero, 0, 1, false, full.expanded);
    EXPECT_FALSE(enough.gave_up);
    EXPECT_EQ(enough.vertices, full.vertices);
    ++found;
  }
  EXPECT_GT(gave_up, 5);
  EXPECT_EQ(found, gave_up);
}

// The cost to the goal is every vertex's Dijkstra distance; computed once and kept while
// edges turn invalid (as the lazy search's look-ahead keeps it past its repair bound),
// it still leads A* to shortest paths, expanding fewer vertices than the metric
// heuristic.
TEST(GraphSearch, CostToGoalStaysAHeuristicWhileEdgesTurnInvalid) {
  ConfigurationMetric metric;
  metric.joint_count = 2;
  std::mt19937 rng(9);
  std::size_t expanded_metric = 0, expanded_cost = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Roadmap roadmap = random_roadmap(metric, &rng);
    for (const bool valid_only : {false, true}) {
      GoalDistances distances;
      distances.compute(roadmap, 1, valid_only);
      const std::vector<double>& to_goal = distances.cost();
      ASSERT_EQ(to_goal.size(), roadmap.vertex_count());
      for (std::uint32_t v = 0; v < roadmap.vertex_count(); v += 17) {
        const double d = dijkstra(roadmap, v, 1, valid_only);
        if (std::isinf(d)) {
          EXPECT_TRUE(std::isinf(to_goal[v]));
        } else {
          EXPECT_NEAR(to_goal[v], d, 1e-4 * std::max(d, 1.0));
        }
      }
      // Edges of each path found turn invalid, one at a time, as lazy PRM finds them.
      Roadmap losing = roadmap;
      for (int round = 0; round < 30; ++round) {
        const GraphPath path = shortest_path(losing, to_goal, 0, 1, valid_only);
        expect_shortest(losing, path, dijkstra(losing, 0, 1, valid_only), valid_only);
        const GraphPath plain = shortest_path(losing, metric, 0, 1, valid_only);
        expanded_cost += path.expanded;
        expanded_metric += plain.expanded;
        if (path.edges.empty()) break;
        losing.edge(path.edges[path.edges.size() / 2]).state = EdgeState::kInvalid;
      }
    }
  }
  EXPECT_LT(expanded_cost, expanded_metric);
}

}  // namespace
}  // namespace gplanner

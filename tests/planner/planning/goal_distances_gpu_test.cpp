// The costs to the goal computed on the GPU (GpuWayCosts) against the host's Dijkstra
// (GoalDistances without a GPU), on seeded random roadmaps: the same costs bit for bit,
// first edges that lead to the goal along least-cost ways, and lazy PRM's use (edges
// turning invalid batch after batch) giving the costs computed afresh.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gplanner/knn_gpu/gpu_way_costs.h"
#include "gplanner/planner/planning/goal_distances.h"
#include "gplanner/planner/planning/graph_search.h"
#include "require_gpu.h"

namespace gplanner {
namespace {

// `vertices` random points in the unit square, each joined to the others within
// `radius` (found through a grid of cells), the states at random (a tenth invalid,
// `valid` of them valid, the others unknown), lengths the distance times a random factor.
Roadmap random_roadmap(std::mt19937* rng, std::uint32_t vertices, float radius,
                       float valid = 0.3f) {
  ConfigurationMetric metric;
  metric.joint_count = 2;
  std::uniform_real_distribution<float> coord(0, 1), factor(1, 1.5f), state(0, 1);
  Roadmap roadmap(2);
  const int cells = std::max(1, static_cast<int>(1 / radius));
  std::vector<std::vector<std::uint32_t>> grid(cells * cells);
  auto cell_of = [&](float x) { return std::min(cells - 1, static_cast<int>(x * cells)); };
  for (std::uint32_t i = 0; i < vertices; ++i) {
    const float q[] = {coord(*rng), coord(*rng)};
    roadmap.add_vertex(q);
    grid[cell_of(q[0]) * cells + cell_of(q[1])].push_back(i);
  }
  for (std::uint32_t a = 0; a < vertices; ++a) {
    const float* qa = roadmap.vertex(a);
    const int cx = cell_of(qa[0]), cy = cell_of(qa[1]);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        if (cx + dx < 0 || cx + dx >= cells || cy + dy < 0 || cy + dy >= cells) continue;
        for (const std::uint32_t b : grid[(cx + dx) * cells + cy + dy]) {
          if (b <= a) continue;
          const float d = configuration_distance(metric, qa, roadmap.vertex(b));
          if (d >= radius) continue;
          const float s = state(*rng);
          roadmap.add_edge(a, b, d * factor(*rng),
                           s < 0.1f           ? EdgeState::kInvalid
                           : s < 0.1f + valid ? EdgeState::kValid
                                              : EdgeState::kUnknown);
        }
      }
    }
  }
  return roadmap;
}

// The first edges lead from every reachable vertex to the goal along least-cost ways.
void expect_ways_to_goal(const Roadmap& roadmap, const GoalDistances& gpu, std::uint32_t goal,
                         bool valid_only) {
  // (GoalDistances keeps its first edges private: following the costs instead, every
  // vertex has a usable edge to a neighbour whose cost plus the length is its own.)
  const std::vector<double>& cost = gpu.cost();
  for (std::uint32_t v = 0; v < roadmap.vertex_count(); ++v) {
    if (v == goal || std::isinf(cost[v])) continue;
    bool tight = false;
    for (const std::uint32_t e : roadmap.edges_at(v)) {
      const RoadmapEdge& edge = roadmap.edge(e);
      if (!usable(edge, valid_only)) continue;
      const std::uint32_t u = edge.a == v ? edge.b : edge.a;
      if (cost[u] + static_cast<double>(edge.length) == cost[v]) tight = true;
    }
    ASSERT_TRUE(tight) << "vertex " << v;
  }
}

// GpuWayCosts itself: costs bit for bit the host's, and first edges that are tight, come
// from a vertex before in (cost, index) order, and reach the goal.
TEST(GpuWayCostsGpu, SameCostsAsTheHostsDijkstra) {
  REQUIRE_GPU();
  GpuWayCosts gpu(0);
  std::mt19937 rng(21);
  for (int trial = 0; trial < 6; ++trial) {
    const std::uint32_t n = trial < 3 ? 500 : 20000;
    const bool valid_only = trial % 2 == 1;  // PRM's: mostly valid edges
    Roadmap roadmap = random_roadmap(&rng, n, trial < 3 ? 0.08f : 0.02f, valid_only ? 0.7f : 0.3f);
    const std::uint32_t goal = n / 3;
    GoalDistances host;
    host.compute(roadmap, goal, valid_only);
    // The rows as GoalDistances reads them.
    std::vector<std::size_t> first(n + 1, 0);
    for (std::uint32_t v = 0; v < n; ++v) first[v + 1] = first[v] + roadmap.edges_at(v).size();
    std::vector<WayEdge> rows(first[n]);
    std::vector<std::uint8_t> usable_edges(roadmap.edge_count());
    for (std::uint32_t v = 0; v < n; ++v) {
      std::size_t i = first[v];
      for (const std::uint32_t e : roadmap.edges_at(v)) {
        const RoadmapEdge& edge = roadmap.edge(e);
        rows[i++] = {edge.a == v ? edge.b : edge.a, e, edge.length};
        usable_edges[e] = usable(edge, valid_only);
      }
    }
    gpu.set_roadmap(100 + trial, first.data(), n, rows.data(), roadmap.edge_count());
    EXPECT_EQ(gpu.roadmap_key(), 100u + trial);
    std::vector<double> cost(n);
    std::vector<std::uint32_t> via(n);
    ASSERT_EQ(gpu.compute(goal, usable_edges.data(), cost.data(), via.data()),
              GpuWayCosts::Outcome::kDone);
    std::size_t reachable = 0;
    for (std::uint32_t v = 0; v < n; ++v) {
      ASSERT_EQ(cost[v], host.cost()[v]) << "trial " << trial << ", vertex " << v;
      if (v == goal || std::isinf(cost[v])) {
        EXPECT_EQ(via[v], GpuWayCosts::kNoEdge);
        continue;
      }
      ++reachable;
      ASSERT_NE(via[v], GpuWayCosts::kNoEdge) << "vertex " << v;
      const RoadmapEdge& edge = roadmap.edge(via[v]);
      ASSERT_TRUE(edge.a == v || edge.b == v);
      ASSERT_TRUE(usable_edges[via[v]]);
      const std::uint32_t u = edge.a == v ? edge.b : edge.a;
      EXPECT_EQ(cost[u] + static_cast<double>(edge.length), cost[v]);
      EXPECT_TRUE(cost[u] < cost[v] || (cost[u] == cost[v] && u < v));
    }
    EXPECT_GT(reachable, n / 2) << "trial " << trial;  // a roadmap worth the test
    EXPECT_GT(gpu.last_rounds(), 1u);
  }
  EXPECT_EQ(gpu.calls(), 6u);
}

// Ways that tie in a circle (a zero-length edge from a vertex to one after it): no first
// edge for the later one, said so; GoalDistances then computes on the host, the same
// costs.
TEST(GpuWayCostsGpu, TiedWaysAreLeftToTheHost) {
  REQUIRE_GPU();
  std::mt19937 rng(22);
  Roadmap roadmap = random_roadmap(&rng, GoalDistances::kGpuVertices, 0.03f);
  // Two vertices apart from the rest: b joined to the goal (0) by an edge of length 1, a
  // to b by one of length 0 and to nothing else: a < b, at the same cost.
  const float far_a[] = {7, 7}, far_b[] = {8, 8};
  Roadmap tied(2);
  for (std::uint32_t v = 0; v < roadmap.vertex_count(); ++v) tied.add_vertex(roadmap.vertex(v));
  const std::uint32_t a = tied.add_vertex(far_a), b = tied.add_vertex(far_b);
  for (const RoadmapEdge& e : roadmap.edges()) tied.add_edge(e.a, e.b, e.length, e.state);
  tied.add_edge(0, b, 1.0f);
  tied.add_edge(a, b, 0.0f);  // a < b, cost(a) == cost(b)
  GoalDistances host, on_gpu;
  host.compute(tied, 0, false);
  ASSERT_EQ(host.cost()[a], 1.0);
  GpuWayCosts gpu(0);
  on_gpu.set_gpu(&gpu);
  on_gpu.compute(tied, 0, false);
  EXPECT_EQ(gpu.calls(), 1u);  // tried there, then on the host
  EXPECT_EQ(on_gpu.cost(), host.cost());
  EXPECT_TRUE(on_gpu.exact());
  expect_ways_to_goal(tied, on_gpu, 0, false);
}

// Lazy PRM's use on a roadmap of 20,000 vertices: the shortest path's edges and others
// turn invalid batch after batch; after each batch the costs kept with the GPU are those
// the host computes afresh, and A* led by them goes along the path.
TEST(GoalDistancesGpu, StayExactWhileEdgesTurnInvalid) {
  REQUIRE_GPU();
  GpuWayCosts gpu(0);
  std::mt19937 rng(23);
  std::size_t batches = 0, computed_again = 0;
  for (int trial = 0; trial < 2; ++trial) {
    const bool valid_only = trial == 1;
    Roadmap roadmap = random_roadmap(&rng, 20000, 0.02f, valid_only ? 0.7f : 0.3f);
    GoalDistances kept;
    kept.set_gpu(&gpu);
    kept.compute(roadmap, 1, valid_only);
    std::uniform_int_distribution<std::size_t> pick_edge(0, roadmap.edge_count() - 1);
    for (int batch = 0; batch < 40; ++batch) {
      const GraphPath path = shortest_path(roadmap, kept.cost(), 0, 1, valid_only);
      if (path.vertices.empty()) break;
      EXPECT_LE(path.expanded, path.vertices.size() + path.vertices.size() / 10 + 2);
      // One of the path's edges and one at random; every fifth batch the goal's edges but
      // the path's last, which leaves much of the roadmap affected.
      std::vector<std::uint32_t> removed = {path.edges[path.edges.size() / 2],
                                            static_cast<std::uint32_t>(pick_edge(rng))};
      if (batch % 5 == 2) {
        for (const std::uint32_t e : roadmap.edges_at(1))
          if (e != path.edges.back()) removed.push_back(e);
      }
      for (const std::uint32_t e : removed) roadmap.edge(e).state = EdgeState::kInvalid;
      const std::size_t calls = gpu.calls();
      kept.remove_edges(roadmap, removed);
      computed_again += gpu.calls() - calls;
      ++batches;
      ASSERT_TRUE(kept.exact());
      GoalDistances fresh;
      fresh.compute(roadmap, 1, valid_only);
      ASSERT_EQ(kept.cost(), fresh.cost()) << "trial " << trial << ", batch " << batch;
    }
  }
  EXPECT_GT(batches, 40u);
  EXPECT_GT(computed_again, 0u);  // some batches affected more than an eighth
}

}  // namespace
}  // namespace gplanner

// The goal distances kept up to date as edges turn invalid, against computing them again
// from scratch, on random roadmaps in the way lazy PRM uses them.

#include "gplanner/planner/planning/goal_distances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "gplanner/planner/planning/graph_search.h"

namespace gplanner {
namespace {

// `vertices` random points in the unit square, each joined to the others within
// `radius` (a roadmap's neighbourhoods), the edges unknown or valid at random. Their
// lengths are the distance times a random factor, so that no two ways tie (the metric of
// two joints sums the coordinates' differences: many ways would).
Roadmap radius_roadmap(std::mt19937* rng, std::uint32_t vertices, float radius) {
  ConfigurationMetric metric;
  metric.joint_count = 2;
  std::uniform_real_distribution<float> coord(0, 1), factor(1, 1.5f);
  std::bernoulli_distribution valid(0.3);
  Roadmap roadmap(2);
  for (std::uint32_t i = 0; i < vertices; ++i) {
    const float q[] = {coord(*rng), coord(*rng)};
    roadmap.add_vertex(q);
  }
  for (std::uint32_t a = 0; a < vertices; ++a) {
    for (std::uint32_t b = a + 1; b < vertices; ++b) {
      const float d = configuration_distance(metric, roadmap.vertex(a), roadmap.vertex(b));
      if (d < radius)
        roadmap.add_edge(a, b, d * factor(*rng),
                         valid(*rng) ? EdgeState::kValid : EdgeState::kUnknown);
    }
  }
  return roadmap;
}

void expect_same_costs(const std::vector<double>& kept, const std::vector<double>& fresh) {
  ASSERT_EQ(kept.size(), fresh.size());
  for (std::size_t v = 0; v < kept.size(); ++v) {
    if (std::isinf(fresh[v])) {
      EXPECT_TRUE(std::isinf(kept[v])) << "vertex " << v;
    } else {
      EXPECT_NEAR(kept[v], fresh[v], 1e-9 * fresh[v]) << "vertex " << v;
    }
  }
}

// Lazy PRM's use: the shortest path's edges and some others turn invalid, batch after
// batch, until start and goal are apart; after each batch the kept costs are those
// computed again, and A* led by them expands the path's vertices and few others.
TEST(GoalDistances, StayExactWhileEdgesTurnInvalid) {
  std::mt19937 rng(5);
  std::size_t batches = 0, affected = 0, vertex_visits = 0, expanded = 0, on_paths = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Roadmap roadmap = radius_roadmap(&rng, 400, 0.12f);
    const bool valid_only = trial % 3 == 2;
    GoalDistances kept;
    kept.compute(roadmap, 1, valid_only);
    std::uniform_int_distribution<std::size_t> pick_edge(0, roadmap.edge_count() - 1);
    for (int batch = 0; batch < 200; ++batch) {
      const GraphPath path = shortest_path(roadmap, kept.cost(), 0, 1, valid_only);
      if (path.vertices.empty()) break;
      expanded += path.expanded;
      on_paths += path.vertices.size();
      std::uniform_int_distribution<std::size_t> on_path(0, path.edges.size() - 1);
      const std::vector<std::uint32_t> removed = {path.edges[on_path(rng)],
                                                  static_cast<std::uint32_t>(pick_edge(rng))};
      for (const std::uint32_t e : removed) roadmap.edge(e).state = EdgeState::kInvalid;
      affected += kept.remove_edges(roadmap, removed);
      vertex_visits += roadmap.vertex_count();
      ++batches;
      GoalDistances fresh;
      fresh.compute(roadmap, 1, valid_only);
      expect_same_costs(kept.cost(), fresh.cost());
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(batches, 200u);
  // Each batch searched again only part of the roadmap...
  EXPECT_LT(affected, vertex_visits / 4);
  // ...and the exact costs led every search along its path (ties aside).
  EXPECT_LE(expanded, on_paths + on_paths / 20);
}

// An edge that most of the roadmap's ways to the goal pass (the goal's only edge, then
// one of a hub's): every cost from the goal again, as exact as a repair; a bound below
// half of the roadmap still changes nothing.
TEST(GoalDistances, RemovingMostWaysComputesEveryCostAgain) {
  std::mt19937 rng(3);
  Roadmap roadmap = radius_roadmap(&rng, 300, 0.15f);
  const float far[] = {5, 5}, beyond[] = {6, 5};
  const std::uint32_t hub = roadmap.add_vertex(far), goal = roadmap.add_vertex(beyond);
  for (std::uint32_t v = 0; v < 300; v += 2) roadmap.add_edge(v, hub, 10, EdgeState::kUnknown);
  const auto goal_edge =
      static_cast<std::uint32_t>(roadmap.add_edge(hub, goal, 1, EdgeState::kUnknown));
  GoalDistances kept;
  kept.compute(roadmap, goal, false);
  ASSERT_TRUE(std::isfinite(kept.cost()[0]));
  // A bound below half: nothing changes (a copy: its costs are then no longer exact).
  GoalDistances bounded = kept;
  roadmap.edge(goal_edge).state = EdgeState::kInvalid;
  EXPECT_EQ(bounded.remove_edges(roadmap, {goal_edge}, 10), 11u);
  EXPECT_EQ(bounded.cost(), kept.cost());
  // No bound: everything again; no vertex but the goal reaches it now.
  EXPECT_EQ(kept.remove_edges(roadmap, {goal_edge}), roadmap.vertex_count());
  GoalDistances fresh;
  fresh.compute(roadmap, goal, false);
  expect_same_costs(kept.cost(), fresh.cost());
  EXPECT_TRUE(std::isinf(kept.cost()[0]) && std::isinf(kept.cost()[hub]));
  EXPECT_EQ(kept.cost()[goal], 0);
}

// Edges no vertex's way to the goal uses change nothing; a valid edge in the list is
// not removed.
TEST(GoalDistances, EdgesOffEveryWayChangeNothing) {
  std::mt19937 rng(8);
  Roadmap roadmap = radius_roadmap(&rng, 300, 0.15f);
  GoalDistances kept;
  kept.compute(roadmap, 1, false);
  const std::vector<double> before = kept.cost();
  const GraphPath path = shortest_path(roadmap, before, 0, 1, false);
  ASSERT_FALSE(path.vertices.empty());
  // Edges on no shortest way to the goal: those whose ends' costs differ by less than
  // the edge's length (neither end reaches the goal best through the other).
  std::vector<std::uint32_t> off_ways;
  for (std::uint32_t e = 0; e < roadmap.edge_count(); ++e) {
    const RoadmapEdge& edge = roadmap.edge(e);
    if (std::fabs(before[edge.a] - before[edge.b]) < 0.9 * edge.length) off_ways.push_back(e);
  }
  ASSERT_GT(off_ways.size(), roadmap.edge_count() / 4);
  for (const std::uint32_t e : off_ways) roadmap.edge(e).state = EdgeState::kInvalid;
  // One of the path's edges in the list, still usable: not removed.
  std::vector<std::uint32_t> listed = off_ways;
  listed.push_back(path.edges.front());
  EXPECT_EQ(kept.remove_edges(roadmap, listed), 0u);
  expect_same_costs(kept.cost(), before);
  GoalDistances fresh;
  fresh.compute(roadmap, 1, false);
  expect_same_costs(kept.cost(), fresh.cost());
}

// compute() reads the roadmap's edges again once it has grown (lazy PRM's next round,
// on the same roadmap object).
TEST(GoalDistances, ComputeReadsAGrownRoadmapAgain) {
  std::mt19937 rng(11);
  Roadmap roadmap = radius_roadmap(&rng, 200, 0.15f);
  GoalDistances kept;
  kept.compute(roadmap, 1, false);
  // A new vertex joined to the goal and to vertex 0 by short edges: vertex 0's way.
  const float q[] = {0.5f, 0.5f};
  const std::uint32_t v = roadmap.add_vertex(q);
  roadmap.add_edge(v, 1, 1e-3f);
  roadmap.add_edge(v, 0, 1e-3f);
  kept.compute(roadmap, 1, false);
  EXPECT_NEAR(kept.cost()[0], 2e-3, 1e-9);
  GoalDistances fresh;
  fresh.compute(roadmap, 1, false);
  expect_same_costs(kept.cost(), fresh.cost());
  // Invalid, not yet removed: the costs stay those of before (a lower bound); removed:
  // those computed afresh.
  const auto to_zero = static_cast<std::uint32_t>(roadmap.find_edge(v, 0));
  roadmap.edge(to_zero).state = EdgeState::kInvalid;
  EXPECT_NEAR(kept.cost()[0], 2e-3, 1e-9);
  EXPECT_GT(kept.remove_edges(roadmap, {to_zero}), 0u);
  fresh.compute(roadmap, 1, false);
  EXPECT_GT(fresh.cost()[0], 2e-3);
  expect_same_costs(kept.cost(), fresh.cost());
}

// A copy (lazy PRM's set-aside search) removes edges of its own: the costs it was copied
// from, and their edges, stay as they were.
TEST(GoalDistances, ACopyRemovesItsOwnEdges) {
  std::mt19937 rng(12);
  Roadmap roadmap = radius_roadmap(&rng, 300, 0.15f);
  GoalDistances kept;
  kept.compute(roadmap, 1, false);
  const std::vector<double> before = kept.cost();
  const GraphPath path = shortest_path(roadmap, before, 0, 1, false);
  ASSERT_GE(path.edges.size(), 2u);
  GoalDistances aside = kept;
  for (const std::uint32_t e : path.edges) roadmap.edge(e).state = EdgeState::kInvalid;
  EXPECT_GT(aside.remove_edges(roadmap, path.edges), 0u);
  EXPECT_GT(aside.cost()[0], before[0]);
  for (const std::uint32_t e : path.edges) roadmap.edge(e).state = EdgeState::kUnknown;
  EXPECT_EQ(kept.cost(), before);
  // The original's edges are all still usable: removing the path's first edge now (its
  // state changed again) repairs from the costs of before.
  roadmap.edge(path.edges.front()).state = EdgeState::kInvalid;
  kept.remove_edges(roadmap, {path.edges.front()});
  GoalDistances fresh;
  fresh.compute(roadmap, 1, false);
  expect_same_costs(kept.cost(), fresh.cost());
}

void expect_same_search(const GraphPath& own, const GraphPath& roadmaps, const char* what) {
  EXPECT_EQ(own.vertices, roadmaps.vertices) << what;
  EXPECT_EQ(own.edges, roadmaps.edges) << what;
  EXPECT_EQ(own.length, roadmaps.length) << what;
  EXPECT_EQ(own.expanded, roadmaps.expanded) << what;
  EXPECT_EQ(own.gave_up, roadmaps.gave_up) << what;
}

// GoalDistances::shortest_path, over its own rows and usability, against graph_search's
// over the roadmap's states, as lazy PRM's batches use it: edges removed exactly, then
// past a bound (the costs stale), then only set unusable; searches whole and cut short.
// Each search matches vertex for vertex and expansion for expansion.
TEST(GoalDistances, ItsSearchesAreTheRoadmapsSearches) {
  std::mt19937 rng(11);
  std::size_t searches = 0, stale = 0, gave_up = 0;
  for (int trial = 0; trial < 9; ++trial) {
    Roadmap roadmap = radius_roadmap(&rng, 400, 0.12f);
    const bool valid_only = trial % 3 == 2;
    GoalDistances kept;
    EXPECT_TRUE(kept.shortest_path(0).vertices.empty());  // nothing computed yet
    kept.compute(roadmap, 1, valid_only);
    std::uniform_int_distribution<std::size_t> pick_edge(0, roadmap.edge_count() - 1);
    for (int batch = 0; batch < 60; ++batch) {
      const std::size_t bound = batch % 4 == 3 ? 40 : ~std::size_t(0);
      const GraphPath own = kept.shortest_path(0, bound);
      const GraphPath roadmaps = shortest_path(roadmap, kept.cost(), 0, 1, valid_only, bound);
      expect_same_search(own, roadmaps, kept.exact() ? "exact" : "stale");
      ++searches;
      stale += !kept.exact();
      gave_up += own.gave_up;
      if (HasFailure()) return;
      if (own.vertices.empty() && !own.gave_up) break;
      std::vector<std::uint32_t> removed = {static_cast<std::uint32_t>(pick_edge(rng)),
                                            static_cast<std::uint32_t>(pick_edge(rng))};
      if (!own.edges.empty()) removed.push_back(own.edges[own.edges.size() / 2]);
      for (const std::uint32_t e : removed) roadmap.edge(e).state = EdgeState::kInvalid;
      if (!kept.exact()) {
        kept.set_unusable(roadmap, removed);
      } else if (kept.remove_edges(roadmap, removed, batch < 20 ? ~std::size_t(0) - 1 : 3) > 3 &&
                 batch >= 20) {
        EXPECT_FALSE(kept.exact());
      }
    }
  }
  EXPECT_GT(searches, 300u);
  EXPECT_GT(stale, 50u);  // searches led by stale costs were compared too
  EXPECT_GT(gave_up, 10u);
}

// set_unusable changes no cost; the costs stay exact while no way to the goal used the
// edges.
TEST(GoalDistances, SetUnusableKeepsTheCosts) {
  std::mt19937 rng(12);
  Roadmap roadmap = radius_roadmap(&rng, 300, 0.15f);
  GoalDistances kept;
  kept.compute(roadmap, 1, false);
  const std::vector<double> before = kept.cost();
  const GraphPath path = kept.shortest_path(0);
  ASSERT_FALSE(path.edges.empty());
  // An edge on no vertex's way: still exact.
  std::uint32_t off_ways = 0;
  for (std::uint32_t e = 0; e < roadmap.edge_count(); ++e) {
    GoalDistances copy = kept;
    const EdgeState was = roadmap.edge(e).state;
    roadmap.edge(e).state = EdgeState::kInvalid;
    copy.set_unusable(roadmap, {e});
    roadmap.edge(e).state = was;
    if (copy.exact()) {
      off_ways = e;
      break;
    }
  }
  roadmap.edge(off_ways).state = EdgeState::kInvalid;
  kept.set_unusable(roadmap, {off_ways});
  EXPECT_TRUE(kept.exact());
  // The shortest path's first edge: no longer exact, the same costs, and the search
  // goes around it.
  roadmap.edge(path.edges[0]).state = EdgeState::kInvalid;
  kept.set_unusable(roadmap, {path.edges[0]});
  EXPECT_FALSE(kept.exact());
  EXPECT_EQ(kept.cost(), before);
  const GraphPath around = kept.shortest_path(0);
  EXPECT_EQ(std::count(around.edges.begin(), around.edges.end(), path.edges[0]), 0);
  expect_same_search(around, shortest_path(roadmap, kept.cost(), 0, 1, false), "around");
}

}  // namespace
}  // namespace gplanner

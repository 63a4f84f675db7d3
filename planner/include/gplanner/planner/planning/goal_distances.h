#pragma once
// Every roadmap vertex's least cost to the goal over the usable edges (Dijkstra from the
// goal), kept exact while edges become invalid: only the vertices whose way to the goal
// used a removed edge are searched again, from their neighbours whose costs still hold.
// Lazy PRM uses it as A*'s heuristic; exact, it leads the search straight along the
// shortest path (a lower bound that only grows stale leads it around more and more of
// the roadmap: on the humanoid, seed 2, the searches expanded 9x more vertices, and the
// search was most of the plan's time).
//
// compute() reads the roadmap's edges into rows by vertex (each edge's other end, index
// and length, in the order of the edges' indices) and their usability; remove_edges()
// and further compute() calls on the same roadmap, with as many vertices and edges,
// reuse the rows (copies of a GoalDistances share them). So the edges' ends and lengths
// must not change between these calls, and the costs follow the states that the edges
// had at compute() and the edges given to remove_edges() since: another edge that turns
// unusable is still counted usable (the costs stay a lower bound), and an edge that
// turns usable (unknown to valid, with valid_edges_only) is not (call compute() again).
//
// Given a GPU (set_gpu), compute() runs there on roadmaps of kGpuVertices vertices or
// more (GpuWayCosts: the same costs bit for bit, first edges that may differ where ways
// tie), and remove_edges() computes every cost again there once more than an eighth of
// the vertices are affected, rather than a half: on lazy PRM's roadmaps of the rigid
// bodies (16,000 to 64,000 milestones) a Dijkstra over the host's memory took most of
// the plan.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "gplanner/knn_gpu/gpu_way_costs.h"
#include "gplanner/planner/planning/graph_search.h"
#include "gplanner/planner/planning/roadmap.h"

namespace gplanner {

class GoalDistances {
 public:
  // The fewest vertices whose costs compute() computes on the GPU given.
  static constexpr std::size_t kGpuVertices = 4096;

  // The GPU to compute on (nullptr: none), shared by copies; it must outlive them.
  void set_gpu(GpuWayCosts* gpu) { gpu_ = gpu; }

  // Dijkstra from `goal` over the edges not invalid (with valid_edges_only: the valid
  // ones); infinity where a vertex cannot reach the goal.
  void compute(const Roadmap& roadmap, std::uint32_t goal, bool valid_edges_only);

  // `edges` are no longer usable (their states already changed in the roadmap; usable
  // ones among them are ignored): the costs of the vertices whose way to the goal went
  // through one of them are computed again (where that is more than half of all, every
  // cost from the goal again: cheaper than repairing most of the roadmap). Returns how
  // many vertices that was. Where more than `max_affected` would be (max_affected below
  // half of all), it changes no cost and returns max_affected + 1: the costs are then no
  // longer exact (exact() is false until the next compute()), but still a consistent
  // lower bound (taking edges away only lengthens ways), and must not be given edges to
  // remove again (set_unusable() takes them then). Either way the edges are no longer
  // usable to shortest_path().
  std::size_t remove_edges(const Roadmap& roadmap, const std::vector<std::uint32_t>& edges,
                           std::size_t max_affected = ~std::size_t(0) - 1);

  // `edges` are no longer usable (as for remove_edges), and no cost changes: a lower
  // bound still, exact() false where a vertex's way to the goal went through one of
  // them. (Since 0.5.7.)
  void set_unusable(const Roadmap& roadmap, const std::vector<std::uint32_t>& edges);

  // A* from `start` to the goal, led by these costs, over the edges usable at compute()
  // less those given to remove_edges() and set_unusable() since, read from this object's
  // rows of them: the path, expansions included, that graph_search.h's
  // shortest_path(roadmap, cost(), start, goal, valid_edges_only, max_expanded,
  // should_stop) finds while the roadmap's states agree, in 5 to 22 % less time (lazy
  // PRM's searches on the rigid bodies, the H200's host). No path before a compute().
  // (Since 0.5.7.)
  GraphPath shortest_path(std::uint32_t start, std::size_t max_expanded = ~std::size_t(0),
                          const std::function<bool()>& should_stop = {}) const;

  // Whether the costs are exact: since compute(), no remove_edges() left them as they
  // were (max_affected), and no set_unusable() took away a way to the goal.
  bool exact() const { return exact_; }

  // Shape [roadmap.vertex_count()] at the last compute; consistent: cost[v] <=
  // length(v, w) + cost[w] over every usable edge.
  const std::vector<double>& cost() const { return cost_; }

  // Polled every few thousand vertices by compute and remove_edges; true stops them,
  // and stopped() then says the costs are unfinished (not a lower bound: not to be used).
  void set_stop(std::function<bool()> should_stop) { should_stop_ = std::move(should_stop); }
  bool stopped() const { return stopped_; }

 private:
  struct Rows;  // the roadmap's edges by vertex; read once by compute()
  void read_rows(const Roadmap& roadmap);
  // compute() on the GPU; false where it did not (the costs then to compute on the host).
  bool compute_on_gpu(std::uint32_t goal);

  GpuWayCosts* gpu_ = nullptr;
  bool exact_ = false;
  std::shared_ptr<const Rows> rows_;
  std::vector<std::uint8_t> usable_;  // per edge: at compute(), less those removed since
  bool valid_edges_only_ = false;
  std::uint32_t goal_ = 0;
  std::function<bool()> should_stop_;
  bool stopped_ = false;
  std::vector<double> cost_;
  std::vector<std::uint32_t> via_;  // each vertex's first edge on its way to the goal
  // remove_edges' scratch: which vertices it searches again, and their list.
  std::vector<std::uint8_t> affected_;
  std::vector<std::uint32_t> found_;
};

}  // namespace gplanner

#pragma once
// Every vertex's least cost to one vertex (the target) over a roadmap's usable edges, on
// the GPU: the least-cost ways that lazy PRM's search follows (planner's GoalDistances,
// whose Dijkstra is the CPU reference). Rounds of Bellman-Ford: each vertex takes the
// least of its neighbours' costs plus the edge's length, until no cost changes; the
// costs are sums of the edges' float lengths in double, in the order of the way from the
// target, as Dijkstra's are, so both give the same costs bit for bit. Plain C++: no CUDA
// headers.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace gplanner {

// One edge in a vertex's row: its other end, its index, its length.
struct WayEdge {
  std::uint32_t other = 0, edge = 0;
  float length = 0;
};

// Whether it can run here (built with CUDA and a device present); when not, says why in
// *reason (if given).
bool gpu_way_costs_available(std::string* reason = nullptr);

class GpuWayCosts {
 public:
  static constexpr std::uint32_t kNoEdge = ~std::uint32_t(0);

  // On CUDA device `device`. Throws std::runtime_error where no GPU can be used.
  explicit GpuWayCosts(int device);
  ~GpuWayCosts();
  GpuWayCosts(const GpuWayCosts&) = delete;
  GpuWayCosts& operator=(const GpuWayCosts&) = delete;

  // The roadmap, uploaded: `vertices` rows, row v the entries [first[v], first[v + 1])
  // of `rows`, each edge of the roadmap's `edges` in the rows of both its ends. `key`:
  // what the caller tells its roadmaps apart by (roadmap_key() says the last one's; 0
  // before any).
  void set_roadmap(std::uint64_t key, const std::size_t* first, std::size_t vertices,
                   const WayEdge* rows, std::size_t edges);
  std::uint64_t roadmap_key() const;

  enum class Outcome {
    kDone,
    kStopped,  // `should_stop` said to stop: the outputs unfinished
    // A reachable vertex other than the target has no edge to a neighbour before it
    // (lengths that vanish against the costs, so that ways tie in a circle): the costs
    // are right, the first edges not; the caller computes them itself.
    kNoFirstEdge,
  };

  // The costs to `target` (shape [vertices]; infinity where it cannot be reached) over
  // the edges whose usable[e] is not 0 (shape [edges]), and each vertex's first edge on a
  // least-cost way (`via`, shape [vertices]): the first in its row whose other end u has
  // cost[u] + length == cost[v] and comes before v in (cost, index) order, so that
  // following them always reaches the target; kNoEdge for the target and where the cost
  // is infinite. `should_stop` is polled between groups of rounds.
  Outcome compute(std::uint32_t target, const std::uint8_t* usable, double* cost,
                  std::uint32_t* via, const std::function<bool()>& should_stop = {});

  // compute() calls made, and the rounds of the last one.
  std::size_t calls() const;
  std::size_t last_rounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner

#pragma once
// What a planner reports: the path, and where the time went.

#include <cstddef>
#include <string>
#include <vector>

namespace gplanner {

// Seconds per stage of a plan. Stages that run at once count once: where TreePlanner
// draws a round (sampling, k-NN) while the GPU checks the one before (edge checks), the
// drawing counts only for the time it took beyond the check.
struct PlanTimes {
  double sampling = 0;      // drawing milestones
  double state_checks = 0;  // checking milestones (batches)
  double knn = 0;           // nearest neighbours for the roadmap's edges
  double search = 0;        // graph search
  double edge_checks = 0;   // checking edges (batches)
  double shortcutting = 0;  // shortening the found path (batched checks)
  double total = 0;         // the whole call
};

// GPU calls per stage of a plan (collision checks, k-NN and the search's costs to the
// goal; calls the gpu backend answers on the host are none): a GPU call has a fixed cost of tens to
// hundreds of microseconds, so on easy problems their count, not their size, makes the plan time.
// All 0 on the CPU backends.
struct PlanGpuCalls {
  std::size_t state_checks = 0;  // milestones
  std::size_t knn = 0;
  std::size_t search = 0;        // lazy PRM's costs to the goal (since 0.5.3)
  std::size_t edge_checks = 0;   // edges, and the certification of the found path
  std::size_t shortcutting = 0;
  std::size_t total = 0;         // the whole call
};

struct PlanResult {
  bool solved = false;
  std::vector<float> path;  // shape [waypoints, width]: start ... goal
  double length = 0;        // metric length of the path
  double length_before_shortcut = 0;
  PlanTimes times;
  PlanGpuCalls gpu_calls;
  std::size_t rounds = 0;
  std::size_t milestones = 0;  // roadmap vertices, start and goal included
  std::size_t edges = 0;
  std::size_t edges_checked = 0;
  std::size_t states_checked = 0;
  std::size_t samples_checked = 0;  // edge samples
  std::size_t searches = 0;         // graph searches
  std::size_t edge_batches = 0;     // checker calls for edges, shortcuts and the fine re-check
  std::string stop_reason;          // "solved", "time limit", "stopped"
};

}  // namespace gplanner

#pragma once
// Batched RRT-Connect: two trees, one from the start and one from the goal, grown toward
// random configurations as RRT-Connect grows them (Kuffner and LaValle 2000; OMPL's
// RRTConnect), with many extensions in flight at once so that each round is one checker
// call (as pRRTC batches them on the GPU). A round draws `lanes` configurations, half for
// each tree; for each, the tree's nearest node is extended toward it by at most `range`
// (EXTEND), and the other tree's nearest node toward the new node in steps of `range`
// until it reaches it or is blocked (CONNECT). Every sample of all these motions (at the
// local planner's resolution, their ends included) goes to the checker in one call; an
// extension that is free adds its node, and a connection adds the steps free up to its
// first collision. A connection that reaches its new node joins the trees: the path runs
// from the start through both trees to the goal.
//
// From the ninth round on (where a problem is hard), each round is drawn from the trees
// as the round before it found them, not as it left them, where the last round grown
// when it is drawn (the one before that) added a node for every six lanes or more: its
// lanes extend from and connect to nodes at least a round old. So where calls go to the
// GPU (the checker's calls have a cost), a helper thread draws the next round (its
// targets, nearest nodes and rows) while the GPU checks this one, and a round costs the
// longer of the two, not their sum. On the host (the CPU backends) the threads that
// would draw check, and the next round is drawn before this one is checked: the same
// trees either way. Where a round joins the trees, the round drawn after it is dropped (a
// refused path's subtrees are removed from the trees it saw). The first rounds are not
// drawn ahead, nor where the last round grown added few nodes for its lanes: where a
// round adds a node or two, as on problems whose way out is narrow, the lag would halve
// the trees' progress (measured on the PR2's shipped pr2_reach: 6, 12 and 10 rounds
// became 20, 34 and 38 with every round drawn ahead; from the ninth round, seed 3's 10
// became 23). There a round grows the trees by a node for every 10 to 20 lanes; on
// MotionBenchMaker's hard problems (cage, bookshelves) by one for every 2 to 4, on the
// humanoid by one for every 4 to 6.
//
// The path is then shortcut (path_shortcutting, at the fine resolution) and the shortened
// path certified free whole (CertifiedMotions): the tree path's detours need no
// certificate of their own. Where that fails, the tree path's edges are certified (in
// the same call where calls cost): a tree edge that fails loses its subtree, and the
// rounds go on; where they pass, the tree path is shortcut with certified shortcuts, as
// the roadmap planner's path is. (With PlanOptions::certify_path off, the tree path is
// re-checked at a finer resolution, then shortcut.)
//
// Where lazy PRM must cover the whole space with milestones before a path shows, the
// trees grow from the start and the goal into the free space about them, which is what
// single queries whose start or goal sits in a narrow place (a shelf, a cage) need; no
// roadmap is kept. Where only a few poses pass a doorway between free regions (a piano,
// a helicopter), almost every extension hits a wall and lazy PRM does better
// (planner_choice.h). Seeded and deterministic for a given seed and lane count (with a
// deterministic checker).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/milestone_sampler.h"
#include "gplanner/planner/planning/nearest_node_index.h"
#include "gplanner/planner/planning/path_shortcutting.h"
#include "gplanner/planner/planning/plan_options.h"
#include "gplanner/planner/planning/plan_result.h"

namespace gplanner {

struct Scene;

class TreePlanner {
 public:
  // scene and checker must outlive the planner. Of the options it uses the seed, the time
  // limit, tree_range, tree_lanes, the local planner's resolution, the sampler's
  // rotation_spread, the path check (certify_path, certified, final_check_refinement),
  // shortcutting, progress and should_stop.
  TreePlanner(const Scene& scene, CollisionChecker* checker, const PlanOptions& options);

  // Plans from start to goal (each shape [width], free: callers check them first), until
  // a path is found, the time limit passes, or should_stop says so. Each call starts
  // with new trees.
  PlanResult solve(const float* start, const float* goal);

  // The longest extension, under the planner's metric.
  double range() const { return range_; }
  // Extensions a round (half from each tree).
  std::size_t lanes() const { return lanes_; }
  // Of the last solve(): paths through both trees that failed the path check.
  std::size_t paths_refused() const { return paths_refused_; }
  // The last solve's rounds that were drawn ahead, from the trees as the round before them
  // found them.
  std::size_t rounds_drawn_ahead() const { return rounds_drawn_ahead_; }

 private:
  struct Tree {
    explicit Tree(const ConfigurationMetric& metric) : index(metric) {}
    std::vector<float> nodes;             // shape [n, width]
    std::vector<std::int32_t> parent;     // -1 for the root
    std::vector<std::uint8_t> removed;    // an edge on its way to the root failed the path check
    std::vector<std::uint8_t> certified;  // the edge to its parent passed the path check
    NearestNodeIndex index;               // over `nodes`
    std::size_t size() const { return parent.size(); }
    void clear();
  };
  // A round's extension from tree `from` and connection from the other tree.
  struct Lane {
    int from = 0;               // 0: the start's tree, 1: the goal's
    std::int32_t near = -1;     // the node extended in tree `from`
    std::int32_t other = -1;    // the other tree's node nearest to the new node
    std::vector<float> node;    // the new node
    int extend_samples = 0;     // samples of near -> node, node last
    int connect_samples = 0;    // samples of other -> node, node last
    int connect_step = 0;       // samples per step of `range` along the connection
    bool meets_other = false;   // the new node is `other` itself
    std::size_t first_row = 0;  // the lane's first row in the round's call
  };

  std::int32_t add_node(Tree* tree, const float* q, std::int32_t parent) const;
  // The tree's nearest node to q not removed (its index's), or -1 where the stop came
  // first (polled where may_poll, which sets *stopped; seen in *stopped otherwise).
  std::int32_t nearest(const Tree& tree, const float* q, bool may_poll,
                       std::atomic<bool>* stopped) const;
  // Draws the round's lanes and their samples (rows: shape [*, width]); the first round's
  // first lane is the straight motion from the start to the goal.
  void draw_round(bool first_round, std::vector<Lane>* lanes, std::vector<float>* rows,
                  PlanResult* result);
  // The round's rows checked on the host (the CPU backends), each lane on its own thread
  // with RRT-Connect's early stops: the extension coarse to fine up to a collision, the
  // connection in order up to its first, every lane up to the stop; rows left unchecked
  // stay colliding. Returns the rows checked.
  std::size_t check_on_host(const std::vector<Lane>& lanes, const std::vector<float>& rows,
                            std::vector<std::uint8_t>* colliding);
  // Checks the round's rows (one call) while a helper thread draws the next round into
  // next_lanes and next_rows from the trees as they are; adds the check's time and GPU
  // calls to the edge checks, and to sampling and k-NN the time the drawing took beyond
  // the check.
  void check_beside_next_round(const std::vector<float>& rows, std::vector<std::uint8_t>* colliding,
                               std::vector<Lane>* next_lanes, std::vector<float>* next_rows,
                               PlanResult* result);
  // Grows the trees by the round's verdicts; returns the lane that joined them, or -1.
  int grow(const std::vector<Lane>& lanes, const std::vector<float>& rows,
           const std::vector<std::uint8_t>& colliding, std::int32_t* joined_start,
           std::int32_t* joined_goal);
  // The path from the start's root to the goal's through nodes `s` and `g` (the same
  // configuration), with each edge's tree and child node (shape [waypoints - 1]).
  std::vector<float> path_through(std::int32_t s, std::int32_t g, std::vector<int>* edge_tree,
                                  std::vector<std::int32_t>* edge_child) const;
  void remove_subtree(Tree* tree, std::int32_t node) const;
  // What became of a path through both trees.
  enum class PathOutcome {
    kShortened,  // *found: the path shortcut and certified whole
    kFound,      // *found: the path itself, certified (or re-checked finely), to shortcut
    kRefused,    // an edge failed: its subtree removed
    kStopped,    // the stop came first
  };
  // Checks the path (edges: their tree and child node): with certification and
  // shortcutting, shortcut first and the shortened path certified whole, the path's own
  // edges only where that fails (then, where they pass, *failed_shortcut holds the
  // rounds, for the path's shortcutting to go on from); otherwise the path's edges not
  // yet certified.
  PathOutcome finish_path(const std::vector<float>& path, const std::vector<int>& edge_tree,
                          const std::vector<std::int32_t>& edge_child, bool certify,
                          PlanResult* result, std::vector<float>* found,
                          std::optional<ShortcutRounds>* failed_shortcut);
  const char* why_stop() const;
  double elapsed() const;

  const Scene& scene_;
  CollisionChecker* checker_;
  PlanOptions options_;
  LocalPlanner local_;
  CertifiedMotions certifier_;
  // The path's re-check and the shortcuts' check, at the resolution refined by
  // PlanOptions::final_check_refinement: made once (its motion bound goes over every
  // vertex of the robot's meshes, a tenth of a millisecond of an easy plan's few).
  LocalPlanner fine_;
  MilestoneSampler sampler_;
  double range_ = 0;
  std::size_t lanes_ = 0;
  std::mt19937_64 rng_;
  std::size_t paths_refused_ = 0;
  std::size_t rounds_drawn_ahead_ = 0;
  Tree trees_[2];
  std::chrono::steady_clock::time_point started_;
  std::function<bool()> stop_;
};

}  // namespace gplanner

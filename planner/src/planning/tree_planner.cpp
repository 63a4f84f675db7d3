#include "gplanner/planner/planning/tree_planner.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/planning/path_shortcutting.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/straight_line.h"
#include "stage_timer.h"

namespace gplanner {
namespace {

using Clock = std::chrono::steady_clock;

// Where calls have a fixed cost, a round's lanes fill about rows_per_round(rounds done)
// rows, within these bounds: kRowsPerRound in the first kRoundsPerDoubling rounds, then
// twice as many every kRoundsPerDoubling rounds, up to 2^kMaxDoublings times as many.
// Constants, not the checker's measured call cost: the lanes shape the trees, and a seed
// plans the same trees whatever a call's timing. Easy problems end within a few rounds of
// a few thousand rows, as cheap as a call gets. Hard ones check about as many rows in all
// whatever a round holds (cage 0005: about 1.1 million rows both in 271 rounds of 4,096
// and in 52 growing rounds), so larger rounds cost them fewer calls and fewer rounds of
// host work. Measured (H200, 0333b7b against this, MotionBenchMaker's first 8 problems of each
// scenario, cage 9 to 40, and the 8 slowest other problems of the 700):
// - 4,096 rows throughout: cage's median 60.3 ms, the slow eight's 173 ms;
// - doubling every 16 rounds up to 4 times: 45.9 and 107 ms;
// - every 8 rounds up to 4 times: 42.7 and 94.9 ms;
// - every 8 rounds up to 8 times (these constants): 42.6 and 82.0 ms;
// - the other scenarios and the arms' shipped scenes within their spread (most of their
//   plans end within 8 rounds: the same trees).
// (At a fixed size, d87c831, cage: 62 ms at 2,048 rows, 53 at 4,096, 49 at 8,192, where
// pr2_base_arm and the humanoid took 15 and 17 % longer.)
constexpr std::size_t kRowsPerRound = 4096;
constexpr std::size_t kRoundsPerDoubling = 8, kMaxDoublings = 3;
constexpr std::size_t kMinLanes = 8, kMaxLanes = 8192;

// From this round on, each round is drawn from the trees as the round before it found
// them, where the last round grown when it is drawn (the one before that) added a node
// for every kLanesPerNodeDrawnAhead of its lanes or more (the class comment says why and
// when).
constexpr std::size_t kFirstRoundDrawnAhead = kRoundsPerDoubling + 1;
constexpr std::size_t kLanesPerNodeDrawnAhead = 6;

std::size_t rows_per_round(std::size_t rounds_done) {
  return kRowsPerRound << std::min(kMaxDoublings, rounds_done / kRoundsPerDoubling);
}
// A round's nearest nodes are found, and its rows written, on all threads from about
// half a millisecond of work, below which waking a 16-core host's threads costs as much
// as it saves. The work is estimated per configuration entry: a nanosecond a node
// distance where the index keeps joint columns (an arm), a nanosecond an entry where it
// goes row by row (a floating or planar base: more for the rotation's angle), and a
// little over half a nanosecond an entry a row (StraightLine on an arm, the build host's
// cores: pr2_reach's 15 entries in 8.5 ns; a floating base's rotation costs more).
constexpr double kThreadedWorkNs = 5e5;

bool threaded_nearest(std::size_t distances, bool by_columns, int width) {
  return distances * (by_columns ? 1.0 : width) > kThreadedWorkNs;
}
bool threaded_rows(std::size_t rows, int width) { return rows * 0.6 * width > kThreadedWorkNs; }

}  // namespace

TreePlanner::TreePlanner(const Scene& scene, CollisionChecker* checker, const PlanOptions& options)
    : scene_(scene),
      checker_(checker),
      options_(options),
      local_(scene, checker, planner_local(options.local, options)),
      certifier_(scene, checker, sliced(options.certified, options)),
      fine_(scene, checker,
            refined(planner_local(options.local, options), options.final_check_refinement)),
      sampler_(scene.space, local_.metric(), options.sampler),
      rng_(options.seed),
      trees_{Tree(local_.metric()), Tree(local_.metric())} {
  range_ = options.tree_range > 0 ? options.tree_range
                                  : 0.2 * space_extent(scene.space, local_.metric());
  if (options.tree_lanes > 0) {
    lanes_ = options.tree_lanes;
  } else if (checker->configurations_per_call_cost() > 0) {
    lanes_ = 64;  // until the first round says how many rows a lane has
  } else {
    lanes_ = static_cast<std::size_t>(std::max(2, resolve_thread_count(0)));
  }
}

double TreePlanner::elapsed() const { return seconds_since(started_); }

const char* TreePlanner::why_stop() const { return plan_stop_reason(options_, started_); }

std::int32_t TreePlanner::add_node(Tree* tree, const float* q, std::int32_t parent) const {
  const int width = scene_.space.width();
  tree->nodes.insert(tree->nodes.end(), q, q + width);
  tree->parent.push_back(parent);
  tree->removed.push_back(0);
  tree->certified.push_back(0);
  tree->index.add(q);
  return static_cast<std::int32_t>(tree->size() - 1);
}

void TreePlanner::Tree::clear() {
  nodes.clear();
  parent.clear();
  removed.clear();
  certified.clear();
  index.clear();
}

std::int32_t TreePlanner::nearest(const Tree& tree, const float* q, bool may_poll,
                                  std::atomic<bool>* stopped) const {
  // Large trees take long: the stop condition polled by one thread, the others seeing
  // its flag.
  return tree.index.nearest(
      tree.nodes.data(), q, [&](std::int32_t i) { return tree.removed[i] != 0; },
      [&] {
        if (may_poll && stop_()) stopped->store(true);
        return stopped->load(std::memory_order_relaxed);
      });
}

void TreePlanner::draw_round(bool first_round, std::vector<Lane>* lanes, std::vector<float>* rows,
                             PlanResult* result) {
  const int width = scene_.space.width();
  const ConfigurationMetric& metric = local_.metric();
  const ConfigurationSpace& space = scene_.space;
  // The targets, drawn in order (the generator's sequence does not depend on threads).
  // The first round's first lane is the straight motion from the start to the goal.
  std::vector<float> targets(lanes_ * width);
  {
    const auto started = Clock::now();
    for (std::size_t i = 0; i < lanes_; ++i) sampler_.draw(&rng_, &targets[i * width]);
    result->times.sampling += seconds_since(started);
  }
  if (first_round) std::copy_n(&trees_[1].nodes[0], width, &targets[0]);
  lanes->assign(lanes_, Lane{});
  const auto started = Clock::now();
  const std::size_t tree_nodes = trees_[0].size() + trees_[1].size();
  std::atomic<bool> stopped{false};
  // (Before NearestNodeIndex, MotionBenchMaker's cage 0001, rounds of about 100 lanes
  // over up to 1,600 nodes: the stage took 50.8 ms on a 16-core host's threads, 23.6 ms on
  // a 2-core one's.)
  parallel_for(
      lanes_,
      threaded_nearest(tree_nodes * lanes_, trees_[0].index.by_columns(), width)
          ? resolve_thread_count(0)
          : 1,
      [&](std::size_t begin, std::size_t end, int thread) {
        for (std::size_t i = begin; i < end; ++i) {
          Lane& lane = (*lanes)[i];
          lane.from = static_cast<int>(i % 2);
          const Tree& tree = trees_[lane.from];
          const Tree& other = trees_[1 - lane.from];
          const float* target = &targets[i * width];
          lane.near = nearest(tree, target, thread == 0, &stopped);
          if (lane.near < 0) continue;
          const float* near = &tree.nodes[lane.near * width];
          const double d = distance(metric, near, target);
          if (!(d > 0)) {
            lane.near = -1;  // the target is a node already
            continue;
          }
          lane.node.resize(width);
          const bool direct = first_round && i == 0;
          if (d > range_ && !direct) {
            space.interpolate(near, target, range_ / d, lane.node.data());
          } else {
            std::copy_n(target, width, lane.node.data());
          }
          lane.other = nearest(other, lane.node.data(), thread == 0, &stopped);
          if (lane.other < 0) {
            lane.near = -1;
            continue;
          }
          lane.extend_samples = local_.segments(near, lane.node.data());
          const float* other_node = &other.nodes[lane.other * width];
          lane.connect_samples = local_.segments(other_node, lane.node.data());
          const double connect_distance = distance(metric, other_node, lane.node.data());
          lane.meets_other = !(connect_distance > 0);
          lane.connect_step =
              connect_distance > range_
                  ? std::max(1, static_cast<int>(lane.connect_samples * range_ / connect_distance))
                  : lane.connect_samples;
        }
      },
      1);
  if (stopped) {  // the round is dropped; the caller sees why
    for (Lane& lane : *lanes) lane.near = -1;
  }
  // Each lane's rows: the extension's samples, then the connection's, each ending at the
  // new node itself (the same floats in both, so that the trees meet exactly).
  std::size_t row_count = 0;
  for (Lane& lane : *lanes) {
    if (lane.near < 0) continue;
    lane.first_row = row_count;
    row_count += lane.extend_samples + lane.connect_samples;
  }
  rows->resize(row_count * width);
  parallel_for(
      lanes_, threaded_rows(row_count, width) ? resolve_thread_count(0) : 1,
      [&](std::size_t begin, std::size_t end, int) {
        StraightLine line;
        for (std::size_t i = begin; i < end; ++i) {
          const Lane& lane = (*lanes)[i];
          if (lane.near < 0) continue;
          const float* near = &trees_[lane.from].nodes[lane.near * width];
          const float* other = &trees_[1 - lane.from].nodes[lane.other * width];
          float* row = &(*rows)[lane.first_row * width];
          line.reset(space, near, lane.node.data());
          for (int j = 1; j <= lane.extend_samples; ++j, row += width) {
            if (j == lane.extend_samples) {
              std::copy_n(lane.node.data(), width, row);
            } else {
              line.at(double(j) / lane.extend_samples, row);
            }
          }
          line.reset(space, other, lane.node.data());
          for (int j = 1; j <= lane.connect_samples; ++j, row += width) {
            if (j == lane.connect_samples) {
              std::copy_n(lane.node.data(), width, row);
            } else {
              line.at(double(j) / lane.connect_samples, row);
            }
          }
        }
      },
      1);
  result->times.knn += seconds_since(started);
}

std::size_t TreePlanner::check_on_host(const std::vector<Lane>& lanes,
                                       const std::vector<float>& rows,
                                       std::vector<std::uint8_t>* colliding) {
  const int width = scene_.space.width();
  std::atomic<std::size_t> checked{0};
  // The stop is looked at before every row: a round went on past it for as long as its
  // lanes' rows took, and a heavy robot's long connection is hundreds of rows of 50 to
  // 150 us (the PR2's). A stopped lane's rows left unchecked stay colliding: nothing
  // unchecked joins a tree.
  std::atomic<bool> stopped{false};
  parallel_for(
      lanes.size(), resolve_thread_count(0),
      [&](std::size_t begin, std::size_t end, int) {
        std::size_t lane_checks = 0;
        for (std::size_t i = begin; i < end; ++i) {
          const Lane& lane = lanes[i];
          if (lane.near < 0) continue;
          auto check = [&](int j) {  // row j of the lane; true where it collides (or stopped)
            if (stopped.load(std::memory_order_relaxed)) return true;
            if (stop_ && stop_()) {
              stopped.store(true, std::memory_order_relaxed);
              return true;
            }
            const std::size_t row = lane.first_row + j;
            checker_->check(&rows[row * width], 1, &(*colliding)[row]);
            ++lane_checks;
            return (*colliding)[row] != 0;
          };
          // The extension coarse to fine (the new node first): one collision ends it, and
          // the rows left unchecked stay colliding, as the connection's then do.
          if (check(lane.extend_samples - 1)) continue;
          bool free = true;
          for (const int j : coarse_to_fine_order(lane.extend_samples)) {
            if (check(j - 1)) {
              free = false;
              break;
            }
          }
          if (!free) continue;
          // The connection in order from the other tree, up to its first collision.
          for (int j = 0; j < lane.connect_samples - 1; ++j)
            if (check(lane.extend_samples + j)) break;
          // Its last row is the new node, checked above.
          const std::size_t last = lane.first_row + lane.extend_samples + lane.connect_samples - 1;
          const std::uint8_t* connection = &(*colliding)[lane.first_row + lane.extend_samples];
          if (std::find(connection, connection + lane.connect_samples - 1, 1) ==
              connection + lane.connect_samples - 1)
            (*colliding)[last] = 0;
        }
        checked += lane_checks;
      },
      1);
  return checked;
}

void TreePlanner::check_beside_next_round(const std::vector<float>& rows,
                                          std::vector<std::uint8_t>* colliding,
                                          std::vector<Lane>* next_lanes,
                                          std::vector<float>* next_rows, PlanResult* result) {
  const std::size_t row_count = rows.size() / scene_.space.width();
  double check_seconds = 0;
  std::size_t check_calls = 0;
  auto check = [&] {
    const std::size_t calls_before = checker_->device_calls();
    const auto started = Clock::now();
    checker_->check(rows.data(), row_count, colliding->data());
    check_seconds = seconds_since(started);
    check_calls = checker_->device_calls() - calls_before;
  };
  // Two tasks for two threads: the calling thread (parallel_for's thread 0), whose CUDA
  // state is warm, checks, and a helper draws. Each runner takes the task it prefers
  // unless the other took it first; where no helper is free, the calling thread runs both
  // in turn.
  std::atomic<bool> check_taken{false}, draw_taken{false};
  PlanResult drawing;  // the drawing's own stage times
  const auto started = Clock::now();
  parallel_for(
      2, 2,
      [&](std::size_t, std::size_t, int thread) {
        const bool prefers_check = thread == 0;
        const bool taken = (prefers_check ? check_taken : draw_taken).exchange(true);
        if (prefers_check != taken) {
          check();
        } else {
          draw_round(false, next_lanes, next_rows, &drawing);
        }
      },
      1);
  const double together = seconds_since(started);
  result->times.edge_checks += check_seconds;
  result->gpu_calls.edge_checks += check_calls;
  // The drawing counts only for the time it took beyond the check (beside the check it
  // costs the plan nothing), shared between its stages as they took it: the stages still
  // add up to at most the plan's time.
  const double drawn = drawing.times.sampling + drawing.times.knn;
  if (drawn > 0) {
    const double share = std::min(1.0, std::max(0.0, together - check_seconds) / drawn);
    result->times.sampling += share * drawing.times.sampling;
    result->times.knn += share * drawing.times.knn;
  }
}

int TreePlanner::grow(const std::vector<Lane>& lanes, const std::vector<float>& rows,
                      const std::vector<std::uint8_t>& colliding, std::int32_t* joined_start,
                      std::int32_t* joined_goal) {
  const int width = scene_.space.width();
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    const Lane& lane = lanes[i];
    if (lane.near < 0) continue;
    const std::uint8_t* extension = &colliding[lane.first_row];
    if (std::any_of(extension, extension + lane.extend_samples, [](std::uint8_t c) { return c; }))
      continue;  // RRT-Connect's EXTEND trapped: nothing added
    Tree& tree = trees_[lane.from];
    Tree& other = trees_[1 - lane.from];
    const std::int32_t node = add_node(&tree, lane.node.data(), lane.near);
    // CONNECT: the other tree's steps toward the new node, up to the first collision.
    const std::uint8_t* connection = extension + lane.extend_samples;
    const int free_samples =
        static_cast<int>(std::find(connection, connection + lane.connect_samples, 1) - connection);
    std::int32_t last = lane.other;
    for (int j = lane.connect_step; j <= free_samples; j += lane.connect_step) {
      if (j == lane.connect_samples) break;  // the new node itself: added below
      last = add_node(&other, &rows[(lane.first_row + lane.extend_samples + j - 1) * width], last);
    }
    if (free_samples == lane.connect_samples) {
      if (!lane.meets_other) last = add_node(&other, lane.node.data(), last);
      *joined_start = lane.from == 0 ? node : last;
      *joined_goal = lane.from == 0 ? last : node;
      return static_cast<int>(i);
    }
  }
  return -1;
}

std::vector<float> TreePlanner::path_through(std::int32_t s, std::int32_t g,
                                             std::vector<int>* edge_tree,
                                             std::vector<std::int32_t>* edge_child) const {
  const int width = scene_.space.width();
  std::vector<std::int32_t> to_start;  // s up to the start's root
  for (std::int32_t v = s; v >= 0; v = trees_[0].parent[v]) to_start.push_back(v);
  std::vector<float> path;
  edge_tree->clear();
  edge_child->clear();
  for (auto v = to_start.rbegin(); v != to_start.rend(); ++v) {
    const float* q = &trees_[0].nodes[*v * width];
    path.insert(path.end(), q, q + width);
    if (trees_[0].parent[*v] >= 0) {
      edge_tree->push_back(0);
      edge_child->push_back(*v);
    }
  }
  // g is s's configuration: the goal's tree from g's parent down to its root.
  for (std::int32_t v = g; trees_[1].parent[v] >= 0; v = trees_[1].parent[v]) {
    const float* q = &trees_[1].nodes[trees_[1].parent[v] * width];
    path.insert(path.end(), q, q + width);
    edge_tree->push_back(1);
    edge_child->push_back(v);
  }
  return path;
}

void TreePlanner::remove_subtree(Tree* tree, std::int32_t node) const {
  // Children come after their parents.
  tree->removed[node] = 1;
  for (std::size_t i = node + 1; i < tree->size(); ++i)
    if (tree->parent[i] >= 0 && tree->removed[tree->parent[i]]) tree->removed[i] = 1;
}

TreePlanner::PathOutcome TreePlanner::finish_path(const std::vector<float>& path,
                                                  const std::vector<int>& edge_tree,
                                                  const std::vector<std::int32_t>& edge_child,
                                                  bool certify, PlanResult* result,
                                                  std::vector<float>* found,
                                                  std::optional<ShortcutRounds>* failed_shortcut) {
  failed_shortcut->reset();
  const int width = scene_.space.width();
  std::vector<std::size_t> unchecked;  // the path's edges not yet certified
  for (std::size_t e = 0; e < edge_tree.size(); ++e)
    if (!trees_[edge_tree[e]].certified[edge_child[e]]) unchecked.push_back(e);
  std::vector<float> from, to;
  auto add_segments = [&](const std::vector<float>& p, const std::vector<std::size_t>& segments) {
    for (const std::size_t i : segments) {
      from.insert(from.end(), &p[i * width], &p[(i + 1) * width]);
      to.insert(to.end(), &p[(i + 1) * width], &p[(i + 2) * width]);
    }
  };
  // Applies the certification's verdicts on the tree path's unchecked edges; false where
  // one failed (its subtree removed).
  auto apply = [&](const std::vector<std::uint8_t>& verdicts) {
    bool valid = true;
    for (std::size_t i = 0; i < unchecked.size(); ++i) {
      Tree& tree = trees_[edge_tree[unchecked[i]]];
      const std::int32_t child = edge_child[unchecked[i]];
      if (verdicts[i]) {
        valid = false;
        remove_subtree(&tree, child);
      } else {
        tree.certified[child] = 1;
      }
    }
    return valid;
  };
  std::vector<std::uint8_t> invalid;
  if (certify && options_.shortcut_rounds > 0 && !unchecked.empty()) {
    // Shortcut first, at the fine resolution, then certify the shortened path whole: the
    // tree path's long detours need no certificate where the shortcut passes, and only
    // where it fails are they certified, after it. (Certifying them in the same call, for
    // that case, cost the GPU's plans more than the call it saved: on 35 MotionBenchMaker
    // Panda problems the tree path's edges took 0.74 to 4.5 times the shortened path's
    // certification checks (1.5 times in the median, counted on the cpu backend),
    // sometimes in more rounds, each a call, while one shortened path failed its
    // certification; without them the plans were 1.05x sooner on an H200, the same paths.)
    ShortcutRounds rounds;
    {
      StageTimer timer(&result->times.shortcutting, &result->gpu_calls.shortcutting, *checker_);
      std::mt19937_64 shortcut_rng = shortcut_generator(options_.seed);
      rounds = run_shortcut_rounds(scene_.space, &local_, &fine_, options_.shortcut_rounds,
                                   options_.shortcut_candidates, &shortcut_rng, path);
    }
    const std::vector<float>& shortcut = rounds.shortened;
    std::vector<std::size_t> all(shortcut.size() / width - 1);
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    add_segments(shortcut, all);
    invalid.assign(all.size(), 1);
    {
      StageTimer timer(&result->times.shortcutting, &result->gpu_calls.shortcutting, *checker_);
      if (!certifier_.check_motions(from.data(), to.data(), invalid.size(), invalid.data()))
        return PathOutcome::kStopped;
    }
    if (std::none_of(invalid.begin(), invalid.end(), [](std::uint8_t v) { return v; })) {
      *found = shortcut;
      return PathOutcome::kShortened;
    }
    // The rounds are kept for the shortcutting of the tree path, should it pass: they
    // need not run again, only the earlier rounds' paths be certified.
    *failed_shortcut = std::move(rounds);
    from.clear();
    to.clear();
  }
  // The tree path's unchecked edges, certified (or re-checked finely).
  add_segments(path, unchecked);
  invalid.assign(unchecked.size(), 1);
  {
    StageTimer timer(&result->times.edge_checks, &result->gpu_calls.edge_checks, *checker_);
    MotionChecker* motions = certify ? static_cast<MotionChecker*>(&certifier_) : &fine_;
    if (!motions->check_motions(from.data(), to.data(), unchecked.size(), invalid.data()))
      return PathOutcome::kStopped;
  }
  if (!apply(invalid)) {
    failed_shortcut->reset();
    return PathOutcome::kRefused;
  }
  *found = path;
  return PathOutcome::kFound;
}

PlanResult TreePlanner::solve(const float* start, const float* goal) {
  started_ = Clock::now();
  PlanResult result;
  const std::size_t calls_before = checker_->device_calls();
  local_.reset_stats();
  certifier_.reset_stats();
  fine_.reset_stats();
  const int width = scene_.space.width();
  stop_ = [this] { return why_stop() != nullptr; };
  local_.set_stop(stop_);
  certifier_.set_stop(stop_);
  fine_.set_stop(stop_);
  sampler_.set_endpoints(start, goal);
  for (Tree& tree : trees_) tree.clear();
  add_node(&trees_[0], start, -1);
  add_node(&trees_[1], goal, -1);
  const bool certify = options_.certify_path || options_.edges == EdgeChecks::kCertified;
  const std::size_t call_cost = checker_->configurations_per_call_cost();
  paths_refused_ = 0;
  rounds_drawn_ahead_ = 0;
  std::vector<Lane> lanes, next_lanes;
  std::vector<float> rows, next_rows;
  bool drawn_ahead = false;  // next_lanes and next_rows hold the next round
  std::size_t grown_nodes = 0, grown_lanes = 0;  // what the last round grew, from how many lanes
  std::vector<std::uint8_t> colliding;
  double reported = -1;
  std::vector<float> found;
  bool shortened = false;  // found is the shortcut path, certified
  // Where found is the tree path: the shortcut rounds already run on it, whose path
  // failed its certification.
  std::optional<ShortcutRounds> failed_shortcut;
  while (found.empty()) {
    if (const char* why = why_stop()) {
      result.stop_reason = why;
      break;
    }
    if (drawn_ahead) {
      lanes.swap(next_lanes);
      rows.swap(next_rows);
      drawn_ahead = false;
      ++rounds_drawn_ahead_;
    } else {
      draw_round(result.rounds == 0, &lanes, &rows, &result);
    }
    ++result.rounds;
    const std::size_t row_count = rows.size() / width;
    colliding.assign(row_count, 1);
    // Where a call has a fixed cost, the next round's lanes fill about rows_per_round rows.
    if (options_.tree_lanes == 0 && call_cost > 0 && row_count > 0) {
      const double rows_per_lane = static_cast<double>(row_count) / lanes.size();
      const double rows_wanted = static_cast<double>(rows_per_round(result.rounds));
      lanes_ = std::clamp<std::size_t>(static_cast<std::size_t>(rows_wanted / rows_per_lane),
                                       kMinLanes, kMaxLanes) &
               ~std::size_t(1);
    }
    // The next round drawn ahead, from the trees as this round finds them: beside the
    // GPU's check, or before the host's.
    const bool draw_ahead = result.rounds + 1 >= kFirstRoundDrawnAhead &&
                            grown_nodes * kLanesPerNodeDrawnAhead >= grown_lanes;
    if (call_cost > 0) {
      if (draw_ahead && row_count > 0) {
        check_beside_next_round(rows, &colliding, &next_lanes, &next_rows, &result);
        drawn_ahead = true;
      } else {
        StageTimer timer(&result.times.edge_checks, &result.gpu_calls.edge_checks, *checker_);
        if (row_count > 0) checker_->check(rows.data(), row_count, colliding.data());
      }
      result.samples_checked += row_count;
    } else {
      if (draw_ahead) {
        draw_round(false, &next_lanes, &next_rows, &result);
        drawn_ahead = true;
      }
      StageTimer timer(&result.times.edge_checks, &result.gpu_calls.edge_checks, *checker_);
      result.samples_checked += check_on_host(lanes, rows, &colliding);
    }
    ++result.edge_batches;
    result.edges_checked += 2 * lanes.size();
    std::int32_t s = -1, g = -1;
    const std::size_t nodes_before = trees_[0].size() + trees_[1].size();
    const bool joined = grow(lanes, rows, colliding, &s, &g) >= 0;
    grown_nodes = trees_[0].size() + trees_[1].size() - nodes_before;
    grown_lanes = lanes.size();
    if (joined) {
      drawn_ahead = false;  // a refused path's subtrees are removed from the trees it saw
      std::vector<int> edge_tree;
      std::vector<std::int32_t> edge_child;
      const std::vector<float> path = path_through(s, g, &edge_tree, &edge_child);
      const PathOutcome outcome =
          finish_path(path, edge_tree, edge_child, certify, &result, &found, &failed_shortcut);
      if (outcome == PathOutcome::kRefused) ++paths_refused_;
      if (outcome == PathOutcome::kShortened || outcome == PathOutcome::kFound) {
        result.length_before_shortcut = path_length(local_.metric(), path, width);
        shortened = outcome == PathOutcome::kShortened;
      }
    }
    if (options_.progress && (found.size() || elapsed() - reported >= 0.25)) {
      reported = elapsed();
      const std::size_t nodes = trees_[0].size() + trees_[1].size();
      options_.progress({"edges", result.rounds, nodes, nodes - 2, nodes - 2, reported});
    }
  }
  result.milestones = trees_[0].size() + trees_[1].size();
  result.edges = result.milestones - 2;
  if (!found.empty()) {
    result.solved = true;
    result.stop_reason = "solved";
    result.path = std::move(found);
    result.length = path_length(local_.metric(), result.path, width);
    if (options_.shortcut_rounds > 0 && !shortened) {
      StageTimer timer(&result.times.shortcutting, &result.gpu_calls.shortcutting, *checker_);
      std::mt19937_64 shortcut_rng = shortcut_generator(options_.seed);
      result.length =
          failed_shortcut
              ? certify_shortcut_rounds(scene_.space, &local_, &fine_, &certifier_,
                                        options_.shortcut_rounds, options_.shortcut_candidates,
                                        *failed_shortcut, true, &shortcut_rng, &result.path)
              : shortcut_path(scene_.space, &local_, &fine_, certify ? &certifier_ : nullptr,
                              options_.shortcut_rounds, options_.shortcut_candidates, &shortcut_rng,
                              &result.path);
      if (options_.progress) {
        const std::size_t nodes = result.milestones;
        options_.progress({"shortcut", result.rounds, nodes, nodes - 2, nodes - 2, elapsed()});
      }
    }
  }
  result.samples_checked += local_.stats().samples + certifier_.stats().checks;
  result.edge_batches +=
      local_.stats().batches + fine_.stats().batches + certifier_.stats().batches;
  result.times.total = elapsed();
  result.gpu_calls.total = checker_->device_calls() - calls_before;
  return result;
}

}  // namespace gplanner

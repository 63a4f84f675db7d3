#include "gplanner/planner/planning/roadmap_planner.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <numeric>

#include "gplanner/common/parallel_for.h"
#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/planning/goal_distances.h"
#include "gplanner/planner/planning/graph_search.h"
#include "gplanner/planner/planning/path_shortcutting.h"
#include "gplanner/planner/scene/scene.h"
#include "stage_timer.h"
#include "uninitialized_array.h"

namespace gplanner {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

const char* strategy_name(RoadmapStrategy strategy) {
  return strategy == RoadmapStrategy::kPrm ? "prm" : "lazyprm";
}

bool parse_strategy(const std::string& name, RoadmapStrategy* strategy) {
  if (name == "prm") {
    *strategy = RoadmapStrategy::kPrm;
  } else if (name == "lazyprm") {
    *strategy = RoadmapStrategy::kLazyPrm;
  } else {
    return false;
  }
  return true;
}

RoadmapPlanner::RoadmapPlanner(const Scene& scene, CollisionChecker* checker,
                               NeighborFinder* neighbors, RoadmapStrategy strategy,
                               const PlanOptions& options)
    : scene_(scene),
      checker_(checker),
      neighbors_(neighbors),
      strategy_(strategy),
      options_(options),
      local_(scene, checker, planner_local(options.local, options)),
      certifier_(scene, checker, sliced(options.certified, options)),
      sampler_(scene.space, local_.metric(), options.sampler),
      roadmap_(scene.space.width()),
      rng_(options.seed),
      // Where a call has a fixed cost (a GPU's), the first batch as large as that cost:
      // the first round's milestones in one or two calls rather than a call per growth.
      sampling_batch_(slice_seconds(options),
                      std::max<std::size_t>(128, checker->configurations_per_call_cost()), 64,
                      std::size_t(1) << 22),
      knn_batch_(slice_seconds(options), 1024, 64, std::size_t(1) << 40) {
  fine_.emplace(scene, checker,
                refined(planner_local(options.local, options), options.final_check_refinement));
  neighbors_->reset();
}

void RoadmapPlanner::set_roadmap(Roadmap roadmap) {
  roadmap_ = std::move(roadmap);
  connected_ = 0;
  certified_.clear();
  neighbors_->reset();
  loaded_unchecked_ = roadmap_.vertex_count();
  const ConfigurationMetric& metric = local_.metric();
  valid_edges_ = 0;
  for (std::size_t e = 0; e < roadmap_.edge_count(); ++e) {
    RoadmapEdge& edge = roadmap_.edge(e);
    edge.length = configuration_distance(metric, roadmap_.vertex(edge.a), roadmap_.vertex(edge.b));
    valid_edges_ += edge.state == EdgeState::kValid;
  }
}

bool RoadmapPlanner::check_loaded_milestones(PlanResult* result) {
  std::vector<std::uint8_t> colliding;
  while (loaded_unchecked_ > 0) {
    if (stop_()) return false;
    StageTimer timer(&result->times.state_checks, &result->gpu_calls.state_checks, *checker_,
                     neighbors_);
    const std::size_t count = std::min<std::size_t>(loaded_unchecked_, sampling_batch_.next());
    const std::size_t first = loaded_unchecked_ - count;
    colliding.assign(count, 1);
    const auto started = Clock::now();
    checker_->check(roadmap_.vertex(first), count, colliding.data());
    sampling_batch_.record(count, seconds_since(started));
    result->states_checked += count;
    for (std::size_t i = 0; i < count; ++i) {
      if (!colliding[i]) continue;
      for (const std::uint32_t e : roadmap_.edges_at(first + i))
        set_edge_state(e, EdgeState::kInvalid);
    }
    loaded_unchecked_ = first;
  }
  return true;
}

double RoadmapPlanner::elapsed() const { return seconds_since(started_); }

const char* RoadmapPlanner::why_stop() const { return plan_stop_reason(options_, started_); }

bool RoadmapPlanner::out_of_time(PlanResult* result) const {
  const char* why = why_stop();
  if (why != nullptr) result->stop_reason = why;
  return why != nullptr;
}

void RoadmapPlanner::set_edge_state(std::uint32_t e, EdgeState state) {
  EdgeState& now = roadmap_.edge(e).state;
  if (now == EdgeState::kValid) --valid_edges_;
  if (state == EdgeState::kValid) ++valid_edges_;
  now = state;
}

void RoadmapPlanner::report(const char* stage, const PlanResult& result) const {
  if (!options_.progress) return;
  options_.progress({stage, result.rounds, roadmap_.vertex_count(), roadmap_.edge_count(),
                     valid_edges_, elapsed()});
}

std::size_t RoadmapPlanner::add_milestones(std::size_t count, PlanResult* result) {
  // Batches sized by the milestones found per attempt so far, until `count` are in (or
  // the time is up), and by the measured throughput so that one takes about a slice.
  // Milestones found beyond `count` wait for the next round, so that the roadmap is the
  // same whatever the batches were.
  const int width = scene_.space.width();
  std::size_t added = 0;
  auto take_surplus = [&] {
    const std::size_t n = std::min(count - added, surplus_.size() / width);
    for (std::size_t i = 0; i < n; ++i, ++added) roadmap_.add_vertex(&surplus_[i * width]);
    surplus_.erase(surplus_.begin(), surplus_.begin() + n * width);
  };
  take_surplus();
  while (added < count && !out_of_time(result)) {
    const double yield =
        attempts_ ? std::max(0.01, static_cast<double>(attempts_found_) / attempts_) : 1.0;
    const std::size_t batch = std::min<std::size_t>(
        sampling_batch_.next(), static_cast<std::size_t>(std::ceil((count - added) / yield * 1.1)));
    const auto started = Clock::now();
    std::vector<float> found;
    result->states_checked += sampler_.sample(&rng_, batch, checker_, &found, &result->times);
    sampling_batch_.record(batch, seconds_since(started));
    attempts_ += batch;
    attempts_found_ += found.size() / width;
    surplus_.insert(surplus_.end(), found.begin(), found.end());
    take_surplus();
  }
  return added;
}

bool RoadmapPlanner::connect(PlanResult* result) {
  // The new milestones joined to their k nearest among all milestones, in chunks sized
  // by the measured k-NN time to take about a slice each, so that a stop or the time
  // limit is seen between chunks (one call over millions of new milestones took tens of
  // seconds past the limit). A finder that searches all points in every call (the GPU's)
  // gets them in one call, made only where the last call's time, scaled as the square of
  // the points, says it ends within the time limit.
  StageTimer timer(&result->times.knn, &result->gpu_calls.knn, *checker_, neighbors_);
  const std::size_t n = roadmap_.vertex_count();
  const int k = options_.neighbors;
  const ConfigurationMetric& metric = local_.metric();
  const bool whole = neighbors_->searches_all_points();
  std::vector<int> nearest;
  if (connected_ < n) roadmap_.reserve_edges(roadmap_.edge_count() + (n - connected_) * k);
  // Milestones with no edge yet (from `fresh`: new ones, not a loaded roadmap's): an
  // edge between such a v and w exists only where w came before v in this call and has
  // v among its nearest, so their edges are added without a search of v's edges.
  const std::size_t call_first = std::min(connected_, n);
  std::size_t fresh = n;
  while (fresh > call_first && roadmap_.edges_at(fresh - 1).empty()) --fresh;
  for (std::size_t first = call_first; first < n;) {
    if (out_of_time(result)) return false;
    // The first call of a finder that searches all points, over many: timed first on a
    // prefix, so that its time can be foreseen (quadratic in the points).
    constexpr std::size_t kProbePoints = std::size_t(1) << 16;
    if (whole && knn_last_points_ == 0 && n > kProbePoints) {
      const auto probe_started = Clock::now();
      if (!neighbors_->nearest_of(roadmap_.vertices().data(), kProbePoints, 0, kProbePoints, k,
                                  &nearest)) {
        out_of_time(result);
        return false;
      }
      knn_last_seconds_ = seconds_since(probe_started);
      knn_last_points_ = kProbePoints;
    }
    const double scale = knn_last_points_ ? static_cast<double>(n) / knn_last_points_ : 0;
    if (whole && elapsed() + knn_last_seconds_ * scale * scale > options_.time_limit_s) {
      result->stop_reason = "time limit";
      return false;
    }
    // Parts in units of a query's cost (brute force: n per query), at most 2^18 queries.
    const double cost = neighbors_->query_cost(n);
    const std::size_t queries = static_cast<std::size_t>(std::clamp(
        static_cast<double>(knn_batch_.next()) / cost, 1.0, static_cast<double>(1 << 18)));
    const std::size_t end = whole ? n : std::min(n, first + queries);
    const auto started = Clock::now();
    if (!neighbors_->nearest_of(roadmap_.vertices().data(), n, first, end, k, &nearest)) {
      out_of_time(result);  // the stop that ended it, as the stop reason
      return false;
    }
    knn_last_seconds_ = seconds_since(started);
    knn_last_points_ = n;
    knn_batch_.record(static_cast<std::size_t>((end - first) * cost), knn_last_seconds_);
    auto lists = [&](std::size_t u, std::size_t x, int within) {  // x among u's first nearest
      const int* row = &nearest[(u - first) * k];
      return std::find(row, row + within, static_cast<int>(x)) != row + within;
    };
    // Whether v's j-th nearest u makes a new edge among new milestones: not v itself, not
    // listed before in v's row, and not made already by a new milestone before v that
    // lists v.
    auto makes_edge = [&](std::size_t v, int j) {
      const auto u = static_cast<std::size_t>(nearest[(v - first) * k + j]);
      return u != v && !lists(v, u, j) && !(u >= first && u < v && lists(u, v, k));
    };
    auto length_of = [&](std::size_t i, int j) {
      return configuration_distance(metric, roadmap_.vertex(first + i),
                                    roadmap_.vertex(nearest[i * k + j]));
    };
    const int threads = resolve_thread_count(0);
    if (first >= fresh && first == call_first) {
      // The usual case: the new milestones' edges are all new (none may exist already).
      // In blocks of rows on all cores, first which entries make edges and how many each
      // block has (each entry's test reads `nearest` alone), then each block's edges with
      // their lengths, written from the block's place in the order into storage no thread
      // has touched yet, so that its pages fault on all cores too. (The helicopter's round
      // of 32,000 new milestones on the H200's host, where a page's first write costs
      // about 2 us: 11.6 ms with the edges gathered on one thread, 3.3 ms so.)
      constexpr std::size_t kBlockRows = 512;
      const std::size_t rows = end - first, blocks = (rows + kBlockRows - 1) / kBlockRows;
      const std::unique_ptr<std::uint8_t[]> makes(new std::uint8_t[rows * k]);  // all written
      std::vector<std::size_t> offsets(blocks + 1, 0);  // block b's first edge: offsets[b]
      auto for_each_block = [&](auto&& body) {
        parallel_for(
            blocks, threads,
            [&](std::size_t lo, std::size_t hi, int) {
              for (std::size_t b = lo; b < hi; ++b)
                body(b, b * kBlockRows, std::min(rows, (b + 1) * kBlockRows));
            },
            1);
      };
      for_each_block([&](std::size_t b, std::size_t begin, std::size_t stop) {
        std::size_t count = 0;
        for (std::size_t i = begin; i < stop; ++i) {
          bool listed = true;  // until a row's -1 ends it
          for (int j = 0; j < k; ++j) {
            listed = listed && nearest[i * k + j] >= 0;
            const bool made = listed && makes_edge(first + i, j);
            makes[i * k + j] = made;
            count += made;
          }
        }
        offsets[b + 1] = count;
      });
      std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
      const std::size_t total = offsets.back();
      const detail::UninitializedArray<RoadmapEdge> edges =
          detail::uninitialized_array<RoadmapEdge>(total);
      for_each_block([&](std::size_t b, std::size_t begin, std::size_t stop) {
        std::size_t e = offsets[b];
        for (std::size_t i = begin; i < stop; ++i) {
          for (int j = 0; j < k; ++j) {
            if (!makes[i * k + j]) continue;
            new (&edges[e++]) RoadmapEdge{static_cast<std::uint32_t>(first + i),
                                          static_cast<std::uint32_t>(nearest[i * k + j]),
                                          length_of(i, j), EdgeState::kUnknown};
          }
        }
      });
      roadmap_.append_edges(edges.get(), total);
    } else {
      // The edges' lengths on all cores, then the edges themselves in order, looked for
      // where they may exist.
      std::vector<float> lengths(nearest.size());
      parallel_for(
          end - first, threads,
          [&](std::size_t begin, std::size_t stop, int) {
            for (std::size_t i = begin; i < stop; ++i)
              for (int j = 0; j < k && nearest[i * k + j] >= 0; ++j)
                lengths[i * k + j] = length_of(i, j);
          },
          512);
      for (std::size_t v = first; v < end; ++v) {
        for (int j = 0; j < k; ++j) {
          const int w = nearest[(v - first) * k + j];
          if (w < 0) break;
          const auto a = static_cast<std::uint32_t>(v), b = static_cast<std::uint32_t>(w);
          const float length = lengths[(v - first) * k + j];
          const auto u = static_cast<std::size_t>(w);
          if (v < fresh || (u >= call_first && u < first)) {
            roadmap_.add_edge(a, b, length);  // may exist: looked for
          } else if (makes_edge(v, j)) {
            roadmap_.append_edge(a, b, length);
          }
        }
      }
    }
    connected_ = first = end;
  }
  return true;
}

std::vector<std::uint32_t> RoadmapPlanner::unknown_edges(const GraphPath& path) const {
  std::vector<std::uint32_t> unknown;
  for (const std::uint32_t e : path.edges)
    if (roadmap_.edge(e).state == EdgeState::kUnknown) unknown.push_back(e);
  return unknown;
}

void RoadmapPlanner::add_next_paths(const GoalDistances& to_goal, std::uint32_t s,
                                    std::size_t shortest_vertices,
                                    std::vector<std::uint32_t>* batch, PlanResult* result) {
  // The batch's edges are set aside (marked invalid) while the next path is searched,
  // whose unknown edges join the batch, and so on; then they are unknown again. The
  // shortest valid path is found all the same: the batch only makes more unknown edges
  // known. Stops at a path with no unknown edge (a valid way no longer than any later
  // one), once the batch's samples would fill one checker call, or where setting the
  // batch aside would search again, or a search would expand, more than kSpeculation
  // times the shortest path's vertices (at least kMinSpeculation): with the batch set
  // aside the ways to the goal may have to go around much of the roadmap, which costs
  // more than the checker call it saves. (8 and 256, down from 32 and 1,024 in 0.5.7: on
  // the rigid bodies, seeds 1 to 5 on the H200's host, the search took 22 to 41 % less
  // time, the plans 1.12x less, every path the same; 4 and 128 searched more again.)
  constexpr std::size_t kSpeculation = 8, kMinSpeculation = 256;
  if (options_.lazy_batch_paths <= 1) return;
  const std::size_t max_expanded = std::max(kMinSpeculation, kSpeculation * shortest_vertices);
  const std::size_t sample_budget = options_.local.one_batch_samples;
  auto samples_of = [&](const std::vector<std::uint32_t>& edges) {
    std::size_t samples = 0;
    for (const std::uint32_t e : edges) {
      const RoadmapEdge& edge = roadmap_.edge(e);
      samples += local_.segments(roadmap_.vertex(edge.a), roadmap_.vertex(edge.b)) - 1;
    }
    return samples;
  };
  std::size_t samples = samples_of(*batch);
  for (const std::uint32_t e : *batch) set_edge_state(e, EdgeState::kInvalid);
  // The costs to the goal with the batch set aside, kept exact the same way while that
  // searches again at most kRepair times the shortest path's vertices, so that each
  // search goes straight along the next path (led by to_goal itself the searches went
  // around the set-aside edges: with 64 paths a batch, most of the search time). Past
  // that (the batch cuts through where many ways to the goal go), the last exact costs
  // lead the searches. (8: on the humanoid, pr2_base_arm and the piano a bound of 2
  // searched up to 30 % longer, and max_expanded alone up to 2.3x.)
  constexpr std::size_t kRepair = 8;
  const std::size_t max_repair = std::min(max_expanded, kRepair * shortest_vertices);
  GoalDistances aside = to_goal;
  bool exact = aside.remove_edges(roadmap_, *batch, max_repair) <= max_repair;
  for (int p = 1; p < options_.lazy_batch_paths; ++p) {
    if (aside.stopped()) break;
    const GraphPath next = aside.shortest_path(s, max_expanded, stop_);
    ++result->searches;
    if (next.vertices.empty()) break;
    const std::vector<std::uint32_t> unknown = unknown_edges(next);
    if (unknown.empty()) break;
    samples += samples_of(unknown);
    if (samples > sample_budget) break;
    for (const std::uint32_t e : unknown) {
      set_edge_state(e, EdgeState::kInvalid);
      batch->push_back(e);
    }
    if (exact) {
      exact = aside.remove_edges(roadmap_, unknown, max_repair) <= max_repair;
    } else {
      aside.set_unusable(roadmap_, unknown);  // for its searches; its costs as they are
    }
  }
  for (const std::uint32_t e : *batch) set_edge_state(e, EdgeState::kUnknown);
}

void RoadmapPlanner::set_options(const PlanOptions& options) {
  const bool certified = certifies_path();
  options_ = options;
  if (certifies_path() != certified) certified_.clear();
  fine_.emplace(scene_, checker_,
                refined(planner_local(options.local, options), options.final_check_refinement));
}

bool RoadmapPlanner::certifies_path() const {
  return options_.certify_path || options_.edges == EdgeChecks::kCertified;
}

bool RoadmapPlanner::check_edge_motions(MotionChecker* motions,
                                        const std::vector<std::uint32_t>& edges,
                                        std::vector<std::uint8_t>* invalid) const {
  const int width = scene_.space.width();
  std::vector<float> from(edges.size() * width), to(edges.size() * width);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const RoadmapEdge& e = roadmap_.edge(edges[i]);
    std::copy_n(roadmap_.vertex(e.a), width, &from[i * width]);
    std::copy_n(roadmap_.vertex(e.b), width, &to[i * width]);
  }
  invalid->resize(edges.size());
  return motions->check_motions(from.data(), to.data(), edges.size(), invalid->data());
}

void RoadmapPlanner::check_edges(const std::vector<std::uint32_t>& edges, PlanResult* result) {
  if (edges.empty()) return;
  StageTimer timer(&result->times.edge_checks, &result->gpu_calls.edge_checks, *checker_,
                   neighbors_);
  // In parts of kPart edges (PRM hands over millions), each part's verdicts kept: memory
  // stays bounded, and a stop loses only the part under way, whose edges stay unknown.
  constexpr std::size_t kPart = std::size_t(1) << 18;
  std::vector<std::uint8_t> invalid;
  for (std::size_t first = 0; first < edges.size(); first += kPart) {
    const std::vector<std::uint32_t> part(edges.begin() + first,
                                          edges.begin() + std::min(edges.size(), first + kPart));
    const bool certified = options_.edges == EdgeChecks::kCertified;
    if (!check_edge_motions(certified ? static_cast<MotionChecker*>(&certifier_) : &local_, part,
                            &invalid))
      return;
    for (std::size_t i = 0; i < part.size(); ++i) {
      set_edge_state(part[i], invalid[i] ? EdgeState::kInvalid : EdgeState::kValid);
      if (certified && !invalid[i]) certified_.insert(part[i]);
    }
    result->edges_checked += part.size();
  }
}

PlanResult RoadmapPlanner::solve(const float* start, const float* goal) {
  started_ = Clock::now();
  PlanResult result;
  const std::size_t gpu_calls_before = gpu_calls_of(*checker_, neighbors_);
  local_.reset_stats();
  certifier_.reset_stats();
  const int width = scene_.space.width();
  stop_ = [this] { return why_stop() != nullptr; };
  local_.set_stop(stop_);
  certifier_.set_stop(stop_);
  neighbors_->set_stop(stop_);  // taken back before returning: the finder may outlive us
  const bool loaded_checked = check_loaded_milestones(&result);
  sampler_.set_endpoints(start, goal);
  const std::uint32_t s = roadmap_.add_vertex(start);
  const std::uint32_t g = roadmap_.add_vertex(goal);
  LocalPlanner& fine = *fine_;
  fine.reset_stats();
  fine.set_stop(stop_);
  const bool lazy = strategy_ == RoadmapStrategy::kLazyPrm;
  GraphPath found;
  if (!loaded_checked) out_of_time(&result);  // the stop that came first, as the reason
  for (std::size_t round = 0; loaded_checked && found.vertices.empty(); ++round) {
    if (out_of_time(&result)) break;
    result.rounds = round + 1;
    // The first round samples `milestones` (none more when a loaded roadmap has that
    // many); later rounds double the roadmap.
    const std::size_t have = roadmap_.vertex_count() - 2;
    const std::size_t count = round == 0 ? (have >= options_.milestones ? 0 : options_.milestones)
                                         : std::max(options_.milestones, have);
    if (count > 0 && !fits_in_memory(roadmap_bytes(roadmap_.vertex_count() + count, width,
                                                   options_.neighbors))) {
      result.stop_reason = "memory limit";
      break;
    }
    if (count > 0) {
      // Room for the whole round at once (address space only, until the milestones come):
      // growing a roadmap of a million humanoid milestones copied 180 MB in the middle of a
      // batch, and the plan ended 100 to 150 ms past a 1 s limit.
      roadmap_.reserve_vertices(roadmap_.vertex_count() + count);
      double sampler_seconds = 0;  // the sampler splits its time between two stages itself
      StageTimer calls(&sampler_seconds, &result.gpu_calls.state_checks, *checker_, neighbors_);
      add_milestones(count, &result);
    }
    report("milestones", result);
    if (!connect(&result)) break;
    report("neighbours", result);
    if (!lazy) {
      std::vector<std::uint32_t> unknown;
      for (std::size_t e = 0; e < roadmap_.edge_count(); ++e)
        if (roadmap_.edge(e).state == EdgeState::kUnknown) unknown.push_back(e);
      check_edges(unknown, &result);
      report("edges", result);
    }
    // Search; lazy PRM checks the unknown edges of each path found, until one is valid.
    // The heuristic is every vertex's cost to the search's target (`root`, the goal at
    // first) over this round's roadmap, kept exact as edges turn invalid
    // (GoalDistances), so that each search goes straight along the next shortest path.
    // The roadmap is undirected: where edges found invalid would leave more than half of
    // the costs to repair (edges near the target, which nearly every way passes: in
    // MotionBenchMaker's cage, the way into the cage about the goal), the search turns
    // round, from the goal to the start, led by the costs to the start, computed once;
    // the invalid edges then lie at the far end of most ways, and their repairs are small.
    // Where the finder has a GPU for the costs (NeighborFinder::way_costs), roadmaps of
    // GoalDistances::kGpuVertices or more have them computed there, and a repair past an
    // eighth of the roadmap computes them all again there: the search does not turn.
    std::uint32_t root = g, from = s;
    GoalDistances to_root;
    to_root.set_stop(stop_);
    to_root.set_gpu(neighbors_->way_costs());
    {
      StageTimer timer(&result.times.search, &result.gpu_calls.search, *checker_, neighbors_);
      to_root.compute(roadmap_, root, /*valid_edges_only=*/!lazy);
    }
    if (to_root.stopped()) {
      out_of_time(&result);  // says why
      break;
    }
    // Edges found invalid: removed from to_root's ways, or the search turned round.
    auto remove_invalid = [&](const std::vector<std::uint32_t>& checked) {
      StageTimer timer(&result.times.search, &result.gpu_calls.search, *checker_, neighbors_);
      std::vector<std::uint32_t> removed;
      for (const std::uint32_t e : checked)
        if (roadmap_.edge(e).state == EdgeState::kInvalid) removed.push_back(e);
      to_root.remove_edges(roadmap_, removed, roadmap_.vertex_count() / 2);
      if (!to_root.exact()) {
        std::swap(root, from);
        to_root.compute(roadmap_, root, /*valid_edges_only=*/!lazy);
      }
    };
    while (!out_of_time(&result) && !to_root.stopped()) {
      GraphPath path;
      {
        StageTimer timer(&result.times.search, &result.gpu_calls.search, *checker_, neighbors_);
        path = to_root.shortest_path(from, ~std::size_t(0), stop_);
        ++result.searches;
      }
      if (path.vertices.empty()) break;
      if (root == s) {  // turned round: the path from start to goal
        std::reverse(path.vertices.begin(), path.vertices.end());
        std::reverse(path.edges.begin(), path.edges.end());
      }
      std::vector<std::uint32_t> unknown = unknown_edges(path);
      if (!unknown.empty()) {
        {
          StageTimer timer(&result.times.search, &result.gpu_calls.search, *checker_, neighbors_);
          add_next_paths(to_root, from, path.vertices.size(), &unknown, &result);
        }
        check_edges(unknown, &result);
        remove_invalid(unknown);
        report("edges", result);
        continue;
      }
      // Every edge valid: certify (or re-check finely) the path's edges not yet checked so;
      // an edge failing that is invalid.
      std::vector<std::uint32_t> unchecked;
      for (const std::uint32_t e : path.edges)
        if (!certified_.count(e)) unchecked.push_back(e);
      std::vector<std::uint8_t> invalid;
      bool checked;
      {
        StageTimer timer(&result.times.edge_checks, &result.gpu_calls.edge_checks, *checker_,
                         neighbors_);
        checked =
            check_edge_motions(certifies_path() ? static_cast<MotionChecker*>(&certifier_) : &fine,
                               unchecked, &invalid);
      }
      if (!checked) break;  // stopped: nothing certified
      bool certified = true;
      for (std::size_t i = 0; i < unchecked.size(); ++i) {
        if (invalid[i]) {
          set_edge_state(unchecked[i], EdgeState::kInvalid);
          certified = false;
        } else {
          certified_.insert(unchecked[i]);
        }
      }
      remove_invalid(unchecked);
      if (certified) {
        found = path;
        break;
      }
    }
  }
  result.milestones = roadmap_.vertex_count();
  result.edges = roadmap_.edge_count();
  if (!found.vertices.empty()) {
    result.solved = true;
    result.stop_reason = "solved";
    for (const std::uint32_t v : found.vertices) {
      const float* q = roadmap_.vertex(v);
      result.path.insert(result.path.end(), q, q + width);
    }
    result.length_before_shortcut = path_length(local_.metric(), result.path, width);
    result.length = result.length_before_shortcut;
    if (options_.shortcut_rounds > 0) {
      StageTimer timer(&result.times.shortcutting, &result.gpu_calls.shortcutting, *checker_,
                       neighbors_);
      std::mt19937_64 shortcut_rng = shortcut_generator(options_.seed);
      result.length = shortcut_path(
          scene_.space, &local_, &fine, certifies_path() ? &certifier_ : nullptr,
          options_.shortcut_rounds, options_.shortcut_candidates, &shortcut_rng, &result.path);
      report("shortcut", result);
    }
  }
  result.samples_checked = local_.stats().samples + certifier_.stats().checks;
  result.edge_batches = local_.stats().batches + fine.stats().batches + certifier_.stats().batches;
  result.times.total = elapsed();
  result.gpu_calls.total = gpu_calls_of(*checker_, neighbors_) - gpu_calls_before;
  neighbors_->set_stop(nullptr);
  return result;
}

}  // namespace gplanner

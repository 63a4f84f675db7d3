#include "query_runs.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>
#include <stdexcept>
#include <utility>

#include "harness/bench_config.h"
#include "harness/bench_samples.h"
#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/plan_options.h"
#include "gplanner/planner/planning/scene_metric.h"

namespace gplan {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kCollisionQueries = "collision-queries";
constexpr const char* kLocalPlanning = "local-planning";

// Uniform samples drawn per free milestone wanted before local-planning gives up on a
// scene (a free space below 0.1 % of the configuration space).
constexpr std::size_t kAttemptsPerMilestone = 1000;

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

void require_one_of(const std::string& what, const std::string& name,
                    const std::vector<std::string>& accepted) {
  if (std::find(accepted.begin(), accepted.end(), name) != accepted.end()) return;
  throw std::invalid_argument("unknown " + what + " '" + name + "'; use one of " +
                              joined(accepted));
}

void require_memory(const std::string& what, double bytes) {
  if (gplanner::fits_in_memory(bytes)) return;
  throw std::invalid_argument(
      what + " need about " + gplanner::memory_text(bytes) + ", more than half of this machine's " +
      gplanner::memory_text(gplanner::physical_memory_bytes()) + " of memory; ask for fewer");
}

void check_options(const std::string& table, const QueryTableOptions& options, int width) {
  if (options.repeat < 1)
    throw std::invalid_argument("repeat " + std::to_string(options.repeat) +
                                ": at least one timed call is needed; give 1 or more");
  const double row_bytes = static_cast<double>(width) * sizeof(float);
  if (table == kCollisionQueries) {
    if (options.queries < 1)
      throw std::invalid_argument("queries 0: a batch needs configurations; give 1 or more");
    require_memory(std::to_string(options.queries) + " queries",
                   static_cast<double>(options.queries) * (row_bytes + 2));
  } else {
    if (options.milestones < 2)
      throw std::invalid_argument("milestones " + std::to_string(options.milestones) +
                                  ": a roadmap's edges need 2 or more milestones");
    if (options.neighbors < 1)
      throw std::invalid_argument("neighbors " + std::to_string(options.neighbors) +
                                  ": each milestone needs 1 or more neighbours");
    // The edges' two ends, at most milestones * k of them.
    require_memory(
        std::to_string(options.milestones) + " milestones with " +
            std::to_string(options.neighbors) + " neighbours",
        static_cast<double>(options.milestones) * options.neighbors * (2 * row_bytes + 1));
  }
}

// The roadmap's edges, each undirected edge once: their two ends (shape [edges, width]
// each).
struct RoadmapEdges {
  std::vector<float> from, to;
  std::size_t count = 0;
};

// Each milestone joined to its k nearest under the scene's metric (the CPU finder);
// false once `should_stop` said so.
bool connect_nearest(const gplanner::Scene& scene, const std::vector<float>& milestones, int k,
                     RoadmapEdges* edges, const std::function<bool()>& should_stop) {
  const std::size_t width = scene.space.width();
  const std::size_t n = milestones.size() / width;
  const gplanner::ConfigurationMetric metric = gplanner::make_metric(scene.space, scene.planner);
  const std::unique_ptr<gplanner::NeighborFinder> finder =
      gplanner::make_neighbor_finder(metric, "cpu");
  finder->set_stop(should_stop);
  std::vector<int> nearest;
  if (!finder->nearest_of_new(milestones.data(), n, 0, k, &nearest)) return false;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  pairs.reserve(nearest.size());
  for (std::size_t i = 0; i < n; ++i) {
    for (int m = 0; m < k; ++m) {
      const int j = nearest[i * k + m];
      if (j < 0) continue;
      pairs.emplace_back(std::min<std::size_t>(i, j), std::max<std::size_t>(i, j));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  edges->count = pairs.size();
  edges->from.resize(pairs.size() * width);
  edges->to.resize(pairs.size() * width);
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    std::copy_n(&milestones[pairs[e].first * width], width, &edges->from[e * width]);
    std::copy_n(&milestones[pairs[e].second * width], width, &edges->to[e * width]);
  }
  return true;
}

// The checker for a query-table name and the record's name for what runs.
struct TableChecker {
  std::unique_ptr<gplanner::CollisionChecker> checker;
  std::string name;  // gpu-basic, gpu-packet, gpu-balanced, cpu or fcl
  std::string note;  // the gpu's fallback to the cpu backend, when it fell back
};

TableChecker make_table_checker(const gplanner::Scene& scene, const std::string& name) {
  gplanner::CheckerOptions options;  // threads 0: all cores
  std::string backend = name;
  const std::string gpu_prefix = "gpu-";
  if (name.compare(0, gpu_prefix.size(), gpu_prefix) == 0) {
    backend = "gpu";
    if (!gplanner::parse_traversal(name.substr(gpu_prefix.size()), &options.gpu.traversal))
      throw std::logic_error("query table checker '" + name + "' names no traversal");
    options.gpu.host_calls_up_to = 0;  // the traversal named, at every call size
  }
  TableChecker made;
  made.checker = gplanner::make_collision_checker(scene, backend, options, &made.note);
  // A fallback would put the cpu backend's times under a gpu name, or beside the cpu
  // group's own: the group is refused instead.
  if (made.checker->backend() != backend)
    throw std::runtime_error(fallback_refusal(name, made.note));
  made.name = name;
  return made;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

const std::vector<std::string>& query_table_checkers() {
  static const std::vector<std::string> names{"gpu-basic", "gpu-packet", "gpu-balanced", "cpu",
                                              "fcl"};
  return names;
}

const std::vector<std::string>& query_tables() {
  static const std::vector<std::string> names{kCollisionQueries, kLocalPlanning};
  return names;
}

bool is_query_table(const std::string& planner) {
  return planner == kCollisionQueries || planner == kLocalPlanning;
}

void run_query_group(const gplanner::Scene& scene, const std::string& experiment,
                     const std::string& scene_name, const std::string& table,
                     const std::string& checker, const QueryTableOptions& options,
                     const std::function<void(const BenchRecord&)>& emit,
                     const std::function<bool()>& should_stop) {
  require_one_of("query table", table, query_tables());
  require_one_of("query table checker", checker, query_table_checkers());
  check_options(table, options, scene.space.width());
  const bool queries = table == kCollisionQueries;

  // The workload, untimed, before the checker is made (a GPU's upload is no part of it).
  std::vector<float> configurations;
  RoadmapEdges edges;
  if (queries) {
    configurations = uniform_states(scene, options.queries, options.seed);
  } else {
    gplanner::CpuChecker cpu(scene);
    std::mt19937_64 rng(options.seed);
    const std::vector<float> milestones = free_states(
        scene, &cpu, options.milestones, &rng, should_stop, "local-planning",
        "milestones");
    if (milestones.empty()) return;  // interrupted
    if (!connect_nearest(scene, milestones, options.neighbors, &edges, should_stop)) return;
  }
  const std::size_t work = queries ? options.queries : edges.count;

  TableChecker made = make_table_checker(scene, checker);
  // local-planning: the planner's local planner at the scene's edge resolution, its
  // batches sized by sample count rather than by time as a planner's are (a planner
  // polls its stop every slice), so that every checker gets the same batches.
  std::unique_ptr<gplanner::LocalPlanner> local;
  if (!queries) {
    local = std::make_unique<gplanner::LocalPlanner>(scene, made.checker.get(),
                                                     gplanner::plan_options(scene).local);
    local->set_stop(should_stop);
  }
  // One batch call; false when interrupted.
  auto call = [&](std::uint8_t* verdicts) {
    if (queries) {
      made.checker->check(configurations.data(), work, verdicts);
      return true;
    }
    return local->check_motions(edges.from.data(), edges.to.data(), work, verdicts);
  };

  std::vector<std::uint8_t> warm_up(work), verdicts(work);
  if (should_stop() || !call(warm_up.data())) return;
  for (int run = 0; run < options.repeat; ++run) {
    if (should_stop()) return;
    const auto start = Clock::now();
    if (!call(verdicts.data())) return;
    const double time_s = seconds_since(start);
    if (verdicts != warm_up) {
      throw std::runtime_error("the " + made.name + " checker gave different verdicts for the " +
                               "same " + table + " batch of scene " + scene_name + " (run " +
                               std::to_string(run) + " against the warm-up)");
    }
    BenchRecord record;
    record.experiment = experiment;
    record.scene = scene_name;
    record.planner = table;
    record.checker = made.name;
    record.run = run;
    record.seed = options.seed;
    record.status = "measured";
    record.time_s = time_s;
    record.work = static_cast<long long>(work);
    record.collisions =
        std::count_if(verdicts.begin(), verdicts.end(), [](std::uint8_t v) { return v != 0; });
    record.note = made.note;
    emit(record);
  }
}

}  // namespace gplan

#include "harness/error_time_study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "harness/bench_files.h"
#include "harness/bench_plots.h"
#include "harness/bench_samples.h"
#include "harness/error_time_truth.h"
#include "harness/error_time_workload.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/motion_bound.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/plan_options.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "interruption.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

// The median time of `repeat` calls of `call` after one untimed warm-up (a GPU's
// uploads, a first allocation); false when a call was stopped.
bool timed(int repeat, const std::function<bool()>& call, double* median_s) {
  if (!call()) return false;
  std::vector<double> times;
  for (int r = 0; r < repeat; ++r) {
    const auto start = Clock::now();
    if (!call()) return false;
    times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  *median_s = median(times);
  return true;
}

// A checker under study and the name its points carry.
struct StudyChecker {
  std::string name;  // gpu, gpu-basic, gpu-packet, gpu-balanced, cpu, fcl
  std::unique_ptr<gplanner::CollisionChecker> checker;
};

// The checker `backend` ("gpu", "cpu", "fcl") with `options` on `scene`, or none (and
// `why` set) when a gpu would run on the cpu backend instead.
std::unique_ptr<gplanner::CollisionChecker> make_checker(const gplanner::Scene& scene,
                                                         const std::string& backend,
                                                         const gplanner::CheckerOptions& options,
                                                         std::string* why) {
  std::string fallback;
  std::unique_ptr<gplanner::CollisionChecker> checker =
      gplanner::make_collision_checker(scene, backend, options, &fallback);
  if (checker->backend() != backend) {
    *why = fallback;
    return nullptr;
  }
  return checker;
}

// Everything one scene's study shares: the truth, the workload, the checkers.
class SceneStudy {
 public:
  SceneStudy(const gplanner::Scene& scene, const std::string& scene_name, const BenchConfig& config,
             const std::function<void(const ErrorTimePoint&)>& emit,
             const std::function<void(const std::string&)>& notice,
             const std::function<void(const std::string&)>& progress,
             const std::function<bool()>& stop)
      : scene_(scene),
        name_(scene_name),
        config_(config),
        options_(config.error_time),
        emit_(emit),
        notice_(notice),
        progress_(progress),
        stop_(stop),
        longest_m_(gplanner::MotionBound(scene.robot, scene.space).longest_displacement()) {}

  void run() {
    if (!make_truth()) return;
    make_checkers();
    if (!state_curves() || !edge_curves()) return;
    planning_curves();
  }

 private:
  bool stopped() const { return stop_ && stop_(); }
  std::size_t width() const { return scene_.space.width(); }

  ErrorTimePoint point(const std::string& knob, const std::string& value,
                       const std::string& checker) const {
    ErrorTimePoint p;
    p.scene = name_;
    p.knob = knob;
    p.value = value;
    p.checker = checker;
    return p;
  }

  bool make_truth() {
    const double step_m = options_.truth_step * longest_m_;
    progress_(name_ + ": ground truth (FCL in double, certified at a step of " +
              number_text(step_m) + " m): " + std::to_string(options_.states) + " states, " +
              std::to_string(options_.edges) + " edges");
    const auto start = Clock::now();
    truth_ = std::make_unique<GroundTruth>(scene_, step_m);
    states_ = uniform_states(scene_, options_.states, config_.seed);
    state_truth_ = truth_->states(states_.data(), options_.states);
    const std::size_t milestones =
        options_.roadmap_milestones
            ? options_.roadmap_milestones
            : scene_.planner.roadmap.milestones;
    const int neighbors = scene_.planner.roadmap.neighbors;
    edges_ = study_edges(scene_, truth_->checker(), milestones, neighbors, options_.edges,
                         config_.seed, stop_);
    if (stopped() || edges_.count == 0) return false;
    edge_truth_ = truth_->motions(edges_.from.data(), edges_.to.data(), edges_.count, stop_);
    if (edge_truth_.empty()) return false;
    const auto count = [&](MotionTruth t) {
      return std::count(edge_truth_.begin(), edge_truth_.end(), t);
    };
    progress_(name_ + ": ground truth made in " +
              number_text(std::chrono::duration<double>(Clock::now() - start).count()) +
              " s: " + std::to_string(std::count(state_truth_.begin(), state_truth_.end(), 1)) +
              " of " + std::to_string(options_.states) + " states colliding; " +
              std::to_string(count(MotionTruth::kColliding)) + " of " +
              std::to_string(edges_.count) + " edges colliding, " +
              std::to_string(count(MotionTruth::kFree)) + " free, " +
              std::to_string(count(MotionTruth::kUndecided)) + " undecided");
    return true;
  }

  // The configuration's backends that can run here, in its order.
  void make_checkers() {
    for (const std::string& backend : options_.checkers) {
      std::string why;
      std::unique_ptr<gplanner::CollisionChecker> checker = make_checker(scene_, backend, {}, &why);
      if (!checker) {
        notice_(name_ +
                ": the gpu curves (precision, traversal, delta, edges and planning on "
                "gpu) are left out: no GPU can be used here (" +
                why + ")");
        continue;
      }
      checkers_.push_back({backend, std::move(checker)});
    }
  }

  bool has(const std::string& backend) const {
    return std::any_of(checkers_.begin(), checkers_.end(),
                       [&](const StudyChecker& c) { return c.name == backend; });
  }

  void emit(const ErrorTimePoint& p) { emit_(p); }

  // The states' point of `checker`; false when stopped.
  bool state_point(ErrorTimePoint p, gplanner::CollisionChecker* checker) {
    std::vector<std::uint8_t> verdicts(options_.states);
    if (!timed(
            options_.repeat,
            [&] {
              checker->check(states_.data(), options_.states, verdicts.data());
              return !stopped();
            },
            &p.time_s))
      return false;
    p.missed = p.extra = p.undecided = 0;
    for (std::size_t i = 0; i < options_.states; ++i) {
      if (state_truth_[i] && !verdicts[i]) ++p.missed;
      if (!state_truth_[i] && verdicts[i]) ++p.extra;
    }
    p.total = static_cast<long long>(options_.states);
    emit(p);
    return true;
  }

  bool state_curves() {
    // Precision: float backends against FCL's double (FCL's own point: its time).
    for (const StudyChecker& c : checkers_) {
      if (!state_point(point("precision", c.name == "fcl" ? "double" : "float", c.name),
                       c.checker.get()))
        return false;
    }
    if (has("gpu")) {
      for (const char* traversal : {"basic", "packet", "balanced"}) {
        gplanner::CheckerOptions options;
        gplanner::parse_traversal(traversal, &options.gpu.traversal);
        options.gpu.host_calls_up_to = 0;  // the traversal's own price, at every size
        std::string why;
        const auto gpu = make_checker(scene_, "gpu", options, &why);
        if (!gpu) continue;  // cannot happen: the gpu ran above
        if (!state_point(point("traversal", traversal, std::string("gpu-") + traversal), gpu.get()))
          return false;
      }
    }
    for (const double delta : options_.deltas) {
      gplanner::Scene banded = scene_;  // the checkers keep a reference: it outlives them
      banded.planner.delta_fraction = delta;
      for (const char* backend : {"gpu", "cpu"}) {
        if (!has(backend)) continue;
        std::string why;
        const auto checker = make_checker(banded, backend, {}, &why);
        if (!checker) continue;
        if (!state_point(point("delta", number_text(delta), backend), checker.get())) return false;
      }
    }
    return true;
  }

  // The edges' point of an edge check; false when stopped.
  bool edge_point(ErrorTimePoint p, const std::function<bool(std::uint8_t* invalid)>& check_edges) {
    std::vector<std::uint8_t> invalid(edges_.count);
    if (!timed(
            options_.repeat, [&] { return check_edges(invalid.data()); }, &p.time_s))
      return false;
    p.missed = p.extra = p.undecided = 0;
    for (std::size_t e = 0; e < edges_.count; ++e) {
      if (edge_truth_[e] == MotionTruth::kUndecided) {
        ++p.undecided;
      } else if (edge_truth_[e] == MotionTruth::kColliding && !invalid[e]) {
        ++p.missed;
      } else if (edge_truth_[e] == MotionTruth::kFree && invalid[e]) {
        ++p.extra;
      }
    }
    p.total = static_cast<long long>(edges_.count);
    emit(p);
    return true;
  }

  bool edge_curves() {
    const gplanner::LocalPlannerOptions scene_local = gplanner::plan_options(scene_).local;
    const bool by_displacement = scene_local.max_displacement > 0;
    for (const double factor : options_.edge_resolutions) {
      gplanner::LocalPlannerOptions local = scene_local;
      double value = 0;
      if (by_displacement) {
        value = local.max_displacement = scene_local.max_displacement * factor;
      } else {
        value = local.resolution_fraction = scene_local.resolution_fraction * factor;
      }
      // The scene loader's range: no edge cut into more than kMaxEdgeSegments.
      if (!by_displacement && (value < 1 / gplanner::kMaxEdgeSegments || value > 1)) {
        notice_(name_ + ": edge resolution " + number_text(value) + " (" + number_text(factor) +
                " times the scene's) is outside [1e-5, 1]; that point is left out");
        continue;
      }
      for (const StudyChecker& c : checkers_) {
        gplanner::LocalPlanner planner(scene_, c.checker.get(), local);
        planner.set_stop(stop_);
        const std::string knob = by_displacement ? "max-displacement" : "edge-resolution";
        if (!edge_point(point(knob, number_text(value), c.name), [&](std::uint8_t* invalid) {
              return planner.check_motions(edges_.from.data(), edges_.to.data(), edges_.count,
                                           invalid);
            }))
          return false;
      }
    }
    for (const double fraction : options_.certified_steps) {
      for (const StudyChecker& c : checkers_) {
        gplanner::CertifiedMotionOptions certified;
        certified.step = fraction * longest_m_;
        gplanner::CertifiedMotions motions(scene_, c.checker.get(), certified);
        motions.set_stop(stop_);
        if (!edge_point(point("certified-step", number_text(fraction), c.name),
                        [&](std::uint8_t* invalid) {
                          return motions.check_motions(edges_.from.data(), edges_.to.data(),
                                                       edges_.count, invalid);
                        }))
          return false;
      }
    }
    return true;
  }

  // `runs` seeded plans of ours-lazyprm with `options` on `c`; false when stopped.
  bool plan_point(ErrorTimePoint p, const StudyChecker& c, gplanner::NeighborFinder* neighbors,
                  gplanner::PlanOptions options) {
    std::vector<double> times;
    p.runs = p.total = options_.runs;
    p.solved = p.path_fails = p.path_undecided = 0;
    options.time_limit_s = options_.time_limit_s;
    options.should_stop = stop_;
    for (int run = 0; run < options_.runs; ++run) {
      options.seed = config_.seed + static_cast<std::uint64_t>(run);
      gplanner::RoadmapPlanner planner(scene_, c.checker.get(), neighbors,
                                       gplanner::RoadmapStrategy::kLazyPrm, options);
      const gplanner::PlanResult result = planner.solve(scene_.start.data(), scene_.goal.data());
      if (stopped()) return false;
      times.push_back(result.times.total);
      if (!result.solved) continue;
      ++p.solved;
      const std::string verdict = truth_->path(result.path, stop_);
      if (verdict.empty()) return false;
      if (verdict == "fail") ++p.path_fails;
      if (verdict == "undecided") ++p.path_undecided;
    }
    p.time_s = median(times);
    emit(p);
    return true;
  }

  void planning_curves() {
    for (const StudyChecker& c : checkers_) {
      if (std::find(options_.plan_checkers.begin(), options_.plan_checkers.end(), c.name) ==
          options_.plan_checkers.end())
        continue;
      std::string knn_notice;
      const std::unique_ptr<gplanner::NeighborFinder> neighbors = gplanner::make_neighbor_finder(
          gplanner::make_metric(scene_.space, scene_.planner), c.checker->backend(), &knn_notice);
      if (!knn_notice.empty()) notice_(name_ + ": " + knn_notice);
      for (const double milestones : options_.plan_milestones) {
        gplanner::PlanOptions options = gplanner::plan_options(scene_);
        options.milestones = static_cast<std::size_t>(milestones);
        if (!plan_point(point("milestones", number_text(milestones), c.name), c, neighbors.get(),
                        options))
          return;
      }
      // Sampled edges with the path re-checked at a tenth of the resolution (as before
      // issue 21), sampled edges with the path certified (gplan plan's default), and
      // every edge certified.
      for (const char* value : {"sampled", "sampled+certify", "certified"}) {
        gplanner::PlanOptions options = gplanner::plan_options(scene_);
        options.edges = std::string(value) == "certified" ? gplanner::EdgeChecks::kCertified
                                                          : gplanner::EdgeChecks::kSampled;
        options.certify_path = std::string(value) != "sampled";
        if (!plan_point(point("plan-edges", value, c.name), c, neighbors.get(), options)) return;
      }
    }
  }

  const gplanner::Scene& scene_;
  const std::string name_;
  const BenchConfig& config_;
  const ErrorTimeOptions& options_;
  const std::function<void(const ErrorTimePoint&)>& emit_;
  const std::function<void(const std::string&)>& notice_;
  const std::function<void(const std::string&)>& progress_;
  const std::function<bool()>& stop_;
  const double longest_m_;
  std::unique_ptr<GroundTruth> truth_;
  std::vector<float> states_;
  std::vector<std::uint8_t> state_truth_;
  StudyEdges edges_;
  std::vector<MotionTruth> edge_truth_;
  std::vector<StudyChecker> checkers_;
};

}  // namespace

void run_error_time_scene(const gplanner::Scene& scene, const std::string& scene_name,
                          const BenchConfig& config,
                          const std::function<void(const ErrorTimePoint&)>& emit,
                          const std::function<void(const std::string&)>& notice,
                          const std::function<void(const std::string&)>& progress,
                          const std::function<bool()>& stop) {
  SceneStudy(scene, scene_name, config, emit, notice, progress, stop).run();
}

int run_error_time_study(const BenchConfig& config, const std::vector<gplanner::Scene>& scenes,
                         const std::string& dir, bool plots,
                         const std::function<bool()>& should_stop) {
  const std::string partial = (fs::path(dir) / "results.partial.csv").string();
  std::ofstream partial_csv(partial);
  write_error_time_csv_header(partial_csv);
  std::vector<ErrorTimePoint> points;
  std::vector<std::string> notices;
  const auto say = [](const std::string& line) {
    std::cerr << gplanner::terminal_text(line) << "\n" << std::flush;
  };
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const std::string name = fs::path(config.scenes[s]).stem().string();
    say("[" + std::to_string(s + 1) + "/" + std::to_string(scenes.size()) + "] " + name);
    run_error_time_scene(
        scenes[s], name, config,
        [&](const ErrorTimePoint& p) {
          points.push_back(p);
          write_error_time_csv_line(partial_csv, p);
          partial_csv.flush();
          say("  " + error_time_progress_line(p));
        },
        [&](const std::string& notice) {
          notices.push_back(notice);
          say("notice: " + notice);
        },
        [&](const std::string& line) { say("  " + line); }, should_stop);
    if (should_stop()) break;
  }
  partial_csv.close();
  if (should_stop()) return report_interruption({partial + " (the points measured)"}, {});

  std::ostringstream csv, table;
  write_error_time_csv_header(csv);
  for (const ErrorTimePoint& p : points) write_error_time_csv_line(csv, p);
  write_error_time_table(table, config.name, points, notices);
  write_study_outputs(dir, config.file, csv.str(), table.str(), partial);
  const std::string results = (fs::path(dir) / "results.csv").string();
  if (plots) {
    std::string notice;
    const std::string plot_dir = (fs::path(dir) / "plots").string();
    if (draw_error_time_plots(results, plot_dir, &notice)) {
      std::cerr << "plots: " << plot_dir << "\n";
    } else {
      std::cerr << "notice: no plots: " << gplanner::terminal_text(notice) << "\n";
    }
  }
  return 0;
}

}  // namespace gplan

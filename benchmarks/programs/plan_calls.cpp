// Every checker call of a plan: when it started (from the plan's start), how long it took,
// how many configurations it checked, with or without clearances, and whether the gpu
// backend answered it on the GPU or on the host. The instrument behind issue 33's
// changes to the gpu backend's call cost and routing: where a plan's milliseconds go
// between and within its calls.
//
// For each scene: the gpu backend's routing (measured when the checker is made), then
// `gplan plan`'s planner (auto) run --repeat times with the same checker, a planner made
// anew each time (one line each: plan time, stage times, calls, the time inside them, the
// path's length, rounds and nodes), then the last run's calls, one line each.
//
// --call-cost N: the planner is told that a call costs as much as N configurations, as
// the gpu backend's measured cost tells it, so that the gpu backend's planning (its rounds
// and trees, its host work between calls) can be traced where there is no GPU, the calls
// answered by the backend given.
//
// usage: gplanner_plan_calls SCENE... [--backend gpu|cpu|fcl] [--repeat R] [--seed S]
//                            [--call-cost N]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/plan_options.h"
#include "gplanner/planner/planning/planner_choice.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Call {
  double start_ms, ms;
  std::size_t rows;
  bool clearances, on_gpu;
};

// The checker it wraps, every call recorded.
class RecordingChecker : public gplanner::CollisionChecker {
 public:
  // call_cost: what configurations_per_call_cost() says (0: the checker's own).
  RecordingChecker(gplanner::CollisionChecker* checker, std::size_t call_cost)
      : checker_(checker), call_cost_(call_cost) {}
  std::string backend() const override { return checker_->backend(); }
  void check(const float* q, std::size_t n, std::uint8_t* verdicts) override {
    record(n, false, [&] { checker_->check(q, n, verdicts); });
  }
  void check_clearances(const float* q, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override {
    record(n, true, [&] { checker_->check_clearances(q, n, clearances, verdicts); });
  }
  std::size_t configurations_per_call_cost() const override {
    return call_cost_ > 0 ? call_cost_ : checker_->configurations_per_call_cost();
  }
  std::size_t cheap_calls_up_to() const override {
    return call_cost_ > 0 ? 0 : checker_->cheap_calls_up_to();
  }
  gplanner::CollisionChecker* host_checker() override { return checker_->host_checker(); }
  std::size_t device_calls() const override { return checker_->device_calls(); }
  int gpu_device() const override { return checker_->gpu_device(); }

  void start() {
    calls.clear();
    started_ = Clock::now();
  }
  std::vector<Call> calls;  // since start(), in the order they ended

 private:
  template <typename F>
  void record(std::size_t n, bool clearances, F&& f) {
    const std::size_t device_calls_before = checker_->device_calls();
    const Clock::time_point t = Clock::now();
    f();
    const Clock::time_point end = Clock::now();
    const std::lock_guard<std::mutex> lock(mutex_);  // the cpu backends' threads call at once
    calls.push_back({std::chrono::duration<double, std::milli>(t - started_).count(),
                     std::chrono::duration<double, std::milli>(end - t).count(), n, clearances,
                     checker_->device_calls() != device_calls_before});
  }

  gplanner::CollisionChecker* checker_;
  std::size_t call_cost_;
  Clock::time_point started_;
  std::mutex mutex_;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::string backend = "gpu";
  int repeat = 3;
  unsigned long long seed = 0;
  std::size_t call_cost = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      files.push_back(arg);
      continue;
    }
    if (i + 1 >= argc) {
      std::cerr << arg << " needs a value\n";
      return 2;
    }
    const std::string value = argv[++i];
    if (arg == "--backend") {
      backend = value;
    } else if (arg == "--repeat") {
      repeat = std::max(1, std::atoi(value.c_str()));
    } else if (arg == "--seed") {
      seed = std::strtoull(value.c_str(), nullptr, 10);
    } else if (arg == "--call-cost") {
      call_cost = std::strtoull(value.c_str(), nullptr, 10);
    } else {
      std::cerr << "unknown option " << arg << "\n";
      return 2;
    }
  }
  if (files.empty()) {
    std::cerr << "usage: gplanner_plan_calls SCENE... [--backend gpu|cpu|fcl] [--repeat R] "
                 "[--seed S] [--call-cost N]\n";
    return 2;
  }
  for (const std::string& file : files) {
    const gplanner::Scene scene = gplanner::load_scene(file);
    std::string notice;
    const std::unique_ptr<gplanner::CollisionChecker> checker =
        gplanner::make_collision_checker(scene, backend, {}, &notice);
    if (!notice.empty()) std::cerr << "notice: " << notice << "\n";
    if (const auto* gpu = dynamic_cast<const gplanner::GpuChecker*>(checker.get())) {
      const gplanner::HostCallRouting& r = gpu->routing();
      std::printf(
          "%s: routing: calling thread up to %zu, host threads up to %zu, call cost %zu "
          "configurations, host %.1f us a free configuration\n",
          file.c_str(), r.calling_thread_up_to, r.host_threads_up_to, r.call_cost,
          r.host_seconds_per_configuration * 1e6);
    }
    RecordingChecker recording(checker.get(), call_cost);
    gplanner::PlanOptions options = gplanner::plan_options(scene);
    if (seed > 0) options.seed = seed;
    const std::unique_ptr<gplanner::NeighborFinder> neighbors = gplanner::make_neighbor_finder(
        gplanner::make_metric(scene.space, scene.planner), checker->backend(), nullptr,
        std::max(0, checker->gpu_device()));
    for (int r = 0; r < repeat; ++r) {
      // A planner of its own each run: the same plan again, on a checker already warm.
      gplanner::ChosenPlanner planner(scene, &recording, neighbors.get(),
                                      gplanner::PlannerKind::kAuto, false, options);
      recording.start();
      const gplanner::PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
      double in_calls = 0;
      for (const Call& c : recording.calls) in_calls += c.ms;
      std::printf(
          "%s: run %d: solved %d, plan %.3f ms (k-NN %.3f, edge checks %.3f, "
          "shortcutting %.3f), %zu rounds, %zu nodes, %zu calls taking %.3f ms, length %.4f",
          file.c_str(), r, result.solved ? 1 : 0, result.times.total * 1e3, result.times.knn * 1e3,
          result.times.edge_checks * 1e3, result.times.shortcutting * 1e3, result.rounds,
          result.milestones, recording.calls.size(), in_calls, result.length);
      if (const auto* gpu = dynamic_cast<const gplanner::GpuChecker*>(checker.get()))
        std::printf(", host cost ratio %.2f, host calls up to %zu", gpu->host_cost_ratio(),
                    gpu->host_calls_up_to());
      std::printf("\n");
    }
    for (const Call& c : recording.calls)
      std::printf("  at %8.3f ms  %7.3f ms  %6zu configurations%s on the %s\n", c.start_ms, c.ms,
                  c.rows, c.clearances ? " with clearances" : "", c.on_gpu ? "GPU" : "host");
  }
}

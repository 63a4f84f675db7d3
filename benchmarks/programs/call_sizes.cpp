// What a call of each size costs on each checker, and what one OMPL motion check costs:
// the figures behind the gpu backend's routing (calls of every size fast, issue 22).
//
// For one scene: the gpu backend's measured routing (which call sizes it answers on the
// calling thread, on host threads, on the GPU); then the median time of a call of n
// configurations (n = 1, 4, 16, ..., 4096; seeded uniform samples) on the gpu backend as
// made by default (routed), on the GPU alone, on our core on one host thread and on all
// cores, and on FCL on one thread and on all cores; then the median time of one
// checkMotion on an RRT-like motion (from a sample a tenth of the way towards the next,
// the end included) through the OMPL adapters, against OMPL's DiscreteMotionValidator on
// FCL (as the plugin's users would run without us). Prints Markdown tables.
//
// usage: gplanner_call_sizes SCENE [--repeat R] [--motions M] [--seed S]

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string microseconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, seconds < 1e-3 ? "%.1f us" : "%.0f us", seconds * 1e6);
  return text;
}

struct Named {
  std::string name;
  gplanner::CollisionChecker* checker;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: gplanner_call_sizes SCENE [--repeat R] [--motions M] [--seed S]\n";
    return 2;
  }
  int repeat = 30, motions = 2000;
  unsigned long long seed = 1;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--repeat")
      repeat = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--motions")
      motions = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--seed")
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    else {
      std::cerr << "unknown option " << key << "\n";
      return 2;
    }
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const gplanner::Scene scene = gplanner::load_scene(argv[1]);
  const std::size_t width = scene.space.width();
  const std::size_t most = 4096;
  std::vector<float> q(most * width);
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < most; ++i) scene.space.sample_uniform(&rng, &q[i * width]);

  std::vector<std::unique_ptr<gplanner::CollisionChecker>> owned;
  std::vector<Named> checkers;
  gplanner::GpuChecker* routed = nullptr;
  if (gplanner::query_gpu_device().available) {
    auto gpu = std::make_unique<gplanner::GpuChecker>(scene, gplanner::GpuCheckerOptions{});
    routed = gpu.get();
    checkers.push_back({"gpu (routed)", gpu.get()});
    owned.push_back(std::move(gpu));
    gplanner::GpuCheckerOptions only;
    only.host_calls_up_to = 0;
    owned.push_back(std::make_unique<gplanner::GpuChecker>(scene, only));
    checkers.push_back({"GPU alone", owned.back().get()});
  } else {
    std::cerr << "no GPU: the gpu columns are left out\n";
  }
  owned.push_back(std::make_unique<gplanner::CpuChecker>(scene, 1));
  checkers.push_back({"our core, 1 thread", owned.back().get()});
  owned.push_back(std::make_unique<gplanner::CpuChecker>(scene, 0));
  checkers.push_back({"our core, all cores", owned.back().get()});
  owned.push_back(std::make_unique<gplanner::FclChecker>(scene, 1));
  checkers.push_back({"FCL, 1 thread", owned.back().get()});
  gplanner::CollisionChecker* fcl_one = owned.back().get();
  owned.push_back(std::make_unique<gplanner::FclChecker>(scene, 0));
  checkers.push_back({"FCL, all cores", owned.back().get()});

  std::cout << "## " << argv[1] << "\n\n";
  if (routed) {
    const gplanner::HostCallRouting& r = routed->routing();
    std::cout << "gpu backend routing (measured): calls of up to " << r.calling_thread_up_to
              << " configurations on the calling thread, up to " << r.host_threads_up_to
              << " on host threads, larger on the GPU; one state on one host thread "
              << microseconds(r.host_seconds_per_configuration)
              << " (the mean over 256 uniform samples)\n\n";
  }
  std::cout << "| configurations per call |";
  for (const Named& c : checkers) std::cout << " " << c.name << " |";
  std::cout << "\n| --- |";
  for (std::size_t k = 0; k < checkers.size(); ++k) std::cout << " --- |";
  std::cout << "\n";
  std::vector<std::uint8_t> verdicts(most);
  for (std::size_t n = 1; n <= most; n *= 4) {
    std::cout << "| " << n << " |";
    for (const Named& c : checkers) {
      c.checker->check(q.data(), n, verdicts.data());  // warm-up
      std::vector<double> times;
      // Calls over different rows, so that no call repeats the last one's work.
      for (int r = 0; r < repeat; ++r) {
        const std::size_t offset = (static_cast<std::size_t>(r) * n) % (most - n + 1);
        const auto started = Clock::now();
        c.checker->check(q.data() + offset * width, n, verdicts.data());
        times.push_back(std::chrono::duration<double>(Clock::now() - started).count());
      }
      std::cout << " " << microseconds(median(times)) << " |";
    }
    std::cout << "\n";
    std::cout.flush();
  }

  // One motion at a time, as OMPL's RRTConnect asks.
  std::cout << "\n| one checkMotion (RRT-like motion, end included) | median | mean |\n"
            << "| --- | --- | --- |\n";
  struct Validator {
    std::string name;
    ob::SpaceInformationPtr si;
  };
  std::vector<Validator> validators;
  const auto wire = [&](const std::string& name, gplanner::CollisionChecker* checker, bool ours) {
    og::SimpleSetup setup(gplanner::ompl_adapters::make_state_space(scene));
    ob::SpaceInformationPtr si = setup.getSpaceInformation();
    si->setStateValidityChecker(
        std::make_shared<gplanner::ompl_adapters::StateValidityChecker>(si, scene, checker));
    if (ours) {
      // Sampled, as OMPL's DiscreteMotionValidator beside it samples (the plugin's
      // default certifies).
      si->setMotionValidator(std::make_shared<gplanner::ompl_adapters::MotionValidator>(
          si, scene, checker, gplanner::EdgeChecks::kSampled));
    } else {
      si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
    }
    si->setup();
    validators.push_back({name, si});
  };
  for (const Named& c : checkers) {
    if (c.name.find("all cores") != std::string::npos) continue;
    if (c.checker == fcl_one) continue;
    wire(c.name + ", our motion validator", c.checker, true);
  }
  wire("FCL, 1 thread, OMPL's DiscreteMotionValidator", fcl_one, false);
  for (const Validator& v : validators) {
    ob::State* a = v.si->allocState();
    ob::State* b = v.si->allocState();
    std::vector<float> end(width);
    std::vector<double> times;
    std::size_t valid = 0;
    for (int m = 0; m < motions; ++m) {
      const std::size_t i = static_cast<std::size_t>(m) % (most - 1);
      scene.space.interpolate(&q[i * width], &q[(i + 1) * width], 0.1, end.data());
      gplanner::ompl_adapters::row_to_state(scene, &q[i * width], a);
      gplanner::ompl_adapters::row_to_state(scene, end.data(), b);
      const auto started = Clock::now();
      valid += v.si->checkMotion(a, b);
      times.push_back(std::chrono::duration<double>(Clock::now() - started).count());
    }
    double mean = 0;
    for (const double t : times) mean += t / times.size();
    std::cout << "| " << v.name << " | " << microseconds(median(times)) << " | "
              << microseconds(mean) << " (" << valid << " of " << motions << " valid) |\n";
    v.si->freeState(a);
    v.si->freeState(b);
  }
  return 0;
}

// How the throughput of OMPL-style calls grows with threads: T threads (1, 2, 4, 8, 16
// by default) share one checker behind the state validity checker and the motion
// validator, wired as the README wires them, and each calls isValid on a single state
// and checkMotion on a short motion in turn, for a fixed time or a fixed number of calls.
// States are seeded uniform samples of the scene; a motion goes from one state a fixed
// fraction of the way towards the next (as an RRT's range-limited extensions), its end
// included, every sample in one batch. Prints one JSON line per T: calls, seconds, calls
// per second and the speed-up over the first T. The machine's other load counts in the
// figures: run it alone.
//
// usage: gplanner_thread_scaling SCENE [--backend fcl|cpu|gpu] [--threads 1,2,4,8,16]
//                                [--seconds S | --calls N] [--checker-threads K]
//                                [--motion-fraction F] [--seed S]
//   --seconds S: each T runs for S seconds (default 2); --calls N: each T makes N calls
//   in all, shared among its threads, instead
//   --checker-threads K: the threads the fcl and cpu backends may use inside one call
//   (default 0: all cores, as make_collision_checker gives them)
//   --motion-fraction F: how far towards the next state a motion goes (default 0.1)

#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string backend = "fcl";
  std::vector<int> threads = {1, 2, 4, 8, 16};
  double seconds = 2;
  long long calls = 0;  // > 0: a fixed count instead of a fixed time
  int checker_threads = 0;
  double motion_fraction = 0.1;
  unsigned long long seed = 1;
};

struct Measurement {
  long long is_valid_calls = 0, check_motion_calls = 0;
  double seconds = 0;
};

// T threads call isValid and checkMotion in turn on the states and motions, each thread
// from its own offset, until the time is up or the calls are made.
Measurement measure(int threads, const Options& options, const ob::SpaceInformationPtr& si,
                    const std::vector<ob::State*>& states, const std::vector<ob::State*>& ends) {
  const ob::StateValidityCheckerPtr validity = si->getStateValidityChecker();
  const ob::MotionValidatorPtr motions = si->getMotionValidator();
  const std::size_t n = states.size();
  std::atomic<long long> next_call{0};  // with --calls: the calls handed out so far
  std::atomic<bool> go{false};
  std::atomic<long long> is_valid_calls{0}, check_motion_calls{0};
  std::atomic<int> sink{0};  // keeps the answers alive
  Clock::time_point start, stop;
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&, t] {
      while (!go) std::this_thread::yield();
      long long mine_valid = 0, mine_motion = 0;
      int answers = 0;
      std::size_t k = t * n / threads;
      for (;;) {
        if (options.calls > 0) {
          if (next_call++ >= options.calls) break;
        } else if (Clock::now() >= stop) {
          break;
        }
        const std::size_t i = k++ % n;
        if ((mine_valid + mine_motion) % 2 == 0) {
          answers += validity->isValid(states[i]);
          ++mine_valid;
        } else {
          answers += motions->checkMotion(states[i], ends[i]);
          ++mine_motion;
        }
      }
      is_valid_calls += mine_valid;
      check_motion_calls += mine_motion;
      sink += answers;
    });
  }
  start = Clock::now();
  stop = start + std::chrono::duration_cast<Clock::duration>(
                     std::chrono::duration<double>(options.seconds));
  go = true;
  for (std::thread& thread : pool) thread.join();
  Measurement m;
  m.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  m.is_valid_calls = is_valid_calls;
  m.check_motion_calls = check_motion_calls;
  return m;
}

bool parse(int argc, char** argv, Options* options) {
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string option = argv[i], value = argv[i + 1];
    if (option == "--backend") {
      options->backend = value;
    } else if (option == "--threads") {
      options->threads.clear();
      std::stringstream list(value);
      for (std::string t; std::getline(list, t, ',');)
        options->threads.push_back(std::atoi(t.c_str()));
    } else if (option == "--seconds") {
      options->seconds = std::atof(value.c_str());
    } else if (option == "--calls") {
      options->calls = std::atoll(value.c_str());
    } else if (option == "--checker-threads") {
      options->checker_threads = std::atoi(value.c_str());
    } else if (option == "--motion-fraction") {
      options->motion_fraction = std::atof(value.c_str());
    } else if (option == "--seed") {
      options->seed = std::strtoull(value.c_str(), nullptr, 10);
    } else {
      std::cerr << "gplanner_thread_scaling: unknown option " << option << "\n";
      return false;
    }
  }
  if ((argc - 2) % 2 != 0) {
    std::cerr << "gplanner_thread_scaling: option " << argv[argc - 1] << " needs a value\n";
    return false;
  }
  const bool threads_ok =
      !options->threads.empty() &&
      std::all_of(options->threads.begin(), options->threads.end(), [](int t) { return t > 0; });
  if (!threads_ok || !(options->seconds > 0) || options->calls < 0 ||
      !(options->motion_fraction > 0 && options->motion_fraction <= 1)) {
    std::cerr << "gplanner_thread_scaling: --threads takes positive counts, --seconds a positive "
                 "time, --calls a count, --motion-fraction a fraction in (0, 1]\n";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (argc < 2 || !parse(argc, argv, &options)) {
    std::cerr << "usage: gplanner_thread_scaling SCENE [--backend fcl|cpu|gpu] [--threads "
                 "1,2,4,8,16] [--seconds S | --calls N] [--checker-threads K] "
                 "[--motion-fraction F] [--seed S]\n";
    return 2;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  try {
    const gplanner::Scene scene = gplanner::load_scene(argv[1]);
    gplanner::CheckerOptions checker_options;
    checker_options.threads = options.checker_threads;
    std::string notice;
    const std::unique_ptr<gplanner::CollisionChecker> checker =
        gplanner::make_collision_checker(scene, options.backend, checker_options, &notice);
    if (!notice.empty()) std::cerr << "notice: " << notice << "\n";
    // As the README wires them: one checker behind both adapters.
    og::SimpleSetup setup(gplanner::ompl_adapters::make_state_space(scene));
    const ob::SpaceInformationPtr si = setup.getSpaceInformation();
    setup.setStateValidityChecker(
        std::make_shared<gplanner::ompl_adapters::StateValidityChecker>(si, scene, checker.get()));
    // Sampled, as measured since issue 16 (the plugin's default certifies).
    si->setMotionValidator(std::make_shared<gplanner::ompl_adapters::MotionValidator>(
        si, scene, checker.get(), gplanner::EdgeChecks::kSampled));
    si->setup();

    const std::size_t n = 4096, width = scene.space.width();
    std::vector<float> rows(n * width);
    std::mt19937_64 rng(options.seed);
    for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(&rng, &rows[i * width]);
    std::vector<ob::State*> states(n), ends(n);
    for (std::size_t i = 0; i < n; ++i) {
      states[i] = si->allocState();
      gplanner::ompl_adapters::row_to_state(scene, &rows[i * width], states[i]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      ends[i] = si->allocState();
      si->getStateSpace()->interpolate(states[i], states[(i + 1) % n], options.motion_fraction,
                                       ends[i]);
    }

    // A short warm-up (first-call allocations, the GPU's buffers), not counted.
    Options warm_up = options;
    warm_up.calls = 64;
    measure(1, warm_up, si, states, ends);

    double base_rate = 0;
    for (const int threads : options.threads) {
      const Measurement m = measure(threads, options, si, states, ends);
      const long long calls = m.is_valid_calls + m.check_motion_calls;
      const double rate = calls / m.seconds;
      if (base_rate == 0) base_rate = rate;
      std::cout << std::setprecision(6) << "{\"scene\":\"" << scene.name << "\",\"backend\":\""
                << checker->backend() << "\",\"threads\":" << threads << ",\"calls\":" << calls
                << ",\"is_valid_calls\":" << m.is_valid_calls
                << ",\"check_motion_calls\":" << m.check_motion_calls
                << ",\"seconds\":" << m.seconds << ",\"calls_per_second\":" << rate
                << ",\"speedup\":" << rate / base_rate
                << ",\"baseline_threads\":" << options.threads.front()
                << ",\"checker_threads\":" << options.checker_threads
                << ",\"motion_fraction\":" << options.motion_fraction
                << ",\"hardware_threads\":" << std::thread::hardware_concurrency() << "}"
                << std::endl;
    }
    for (std::size_t i = 0; i < n; ++i) {
      si->freeState(states[i]);
      si->freeState(ends[i]);
    }
  } catch (const std::exception& e) {
    std::cerr << "gplanner_thread_scaling: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

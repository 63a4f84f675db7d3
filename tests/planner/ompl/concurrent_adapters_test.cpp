// The OMPL adapters as the README wires them (one checker behind the state validity
// checker and the motion validator), called from several threads at once: every
// verdict, last valid fraction and counter equals what one thread gets, on each
// backend. GPU cases (names contain "Gpu") skip without a device and assert that it ran.

#include <gtest/gtest.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>

#include <algorithm>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Motion = std::pair<const ob::State*, const ob::State*>;

constexpr int kThreads = 6;

class OmplConcurrentAdapters : public ::testing::TestWithParam<std::string> {};

TEST_P(OmplConcurrentAdapters, EveryAnswerAsOnOneThread) {
  // "GpuRouted": the gpu backend as made by default, small calls answered on the host;
  // "gpu": every call on the GPU.
  const bool routed = GetParam() == "GpuRouted";
  const std::string backend = routed ? "gpu" : GetParam();
  CheckerOptions options;
  if (!routed) options.gpu.host_calls_up_to = 0;
  if (backend == "gpu") {
    const GpuDevice device = query_gpu_device();
    if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  }
  const Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  std::string notice;
  const std::unique_ptr<CollisionChecker> checker =
      make_collision_checker(scene, backend, options, &notice);
  ASSERT_EQ(checker->backend(), backend) << notice;
  // As the README wires them.
  og::SimpleSetup setup(ompl_adapters::make_state_space(scene));
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  const auto validity =
      std::make_shared<ompl_adapters::StateValidityChecker>(si, scene, checker.get());
  setup.setStateValidityChecker(validity);
  si->setMotionValidator(
      std::make_shared<ompl_adapters::MotionValidator>(si, scene, checker.get()));
  si->setup();
  const ob::MotionValidatorPtr validator = si->getMotionValidator();
  auto* batch_validator = dynamic_cast<ompl_adapters::MotionValidator*>(validator.get());

  // Seeded states, and motions from each a part of the way towards the next (short
  // enough that a motion's samples number tens, not hundreds). The validator certifies
  // (its default): on FCL, whose distance queries certify a motion, fewer of them.
  const std::size_t n = backend == "fcl" ? 60 : 600, width = scene.space.width();
  const std::vector<float> rows = testing::sample_configurations(scene, n, 41);
  std::vector<ob::State*> states(n), ends(n);
  std::vector<Motion> motions(n);
  for (std::size_t i = 0; i < n; ++i) {
    states[i] = si->allocState();
    ompl_adapters::row_to_state(scene, &rows[i * width], states[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    ends[i] = si->allocState();
    si->getStateSpace()->interpolate(states[i], states[(i + 1) % n], i % 2 ? 0.1 : 0.25, ends[i]);
    motions[i] = {states[i], ends[i]};
  }

  std::vector<std::uint8_t> valid(n), motion_valid(n);
  std::vector<double> fraction(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    valid[i] = validity->isValid(states[i]);
    std::pair<ob::State*, double> last{nullptr, 1.0};
    motion_valid[i] = validator->checkMotion(states[i], ends[i], last);
    if (!motion_valid[i]) fraction[i] = last.second;
  }
  const std::size_t valid_states = std::count(valid.begin(), valid.end(), 1);
  const std::size_t valid_motions = std::count(motion_valid.begin(), motion_valid.end(), 1);
  ASSERT_GT(valid_states, n / 10);
  ASSERT_LT(valid_states, n - n / 10);
  ASSERT_GT(valid_motions, n / 20);
  ASSERT_LT(valid_motions, n - n / 20);

  // Threads 0 and 3: isValid; 1 and 4: checkMotion with the last valid state; 2 and 5:
  // the batch calls (areValid, checkMotions) a few at a time. Each from its own offset.
  std::vector<std::size_t> wrong(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      ob::State* last_state = si->allocState();
      std::vector<std::uint8_t> answers;
      for (std::size_t k = 0; k < n;) {
        const std::size_t i = (k + t * n / kThreads) % n;
        if (t % 3 == 0) {
          wrong[t] += validity->isValid(states[i]) != static_cast<bool>(valid[i]);
          ++k;
        } else if (t % 3 == 1) {
          std::pair<ob::State*, double> last{last_state, 1.0};
          const bool ok = validator->checkMotion(states[i], ends[i], last);
          wrong[t] +=
              ok != static_cast<bool>(motion_valid[i]) || (!ok && last.second != fraction[i]);
          ++k;
        } else {
          const std::size_t count = std::min<std::size_t>({k % 2 ? 3u : 8u, n - i, n - k});
          validity->areValid({states.begin() + i, states.begin() + i + count}, &answers);
          for (std::size_t j = 0; j < count; ++j) wrong[t] += answers[j] != valid[i + j];
          batch_validator->checkMotions({motions.begin() + i, motions.begin() + i + count},
                                        &answers);
          for (std::size_t j = 0; j < count; ++j) wrong[t] += answers[j] != motion_valid[i + j];
          k += count;
        }
      }
      si->freeState(last_state);
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(wrong[t], 0u) << "thread " << t;
  // One pass on one thread, then each state and motion twice singly and twice in batches.
  EXPECT_EQ(validity->checks(), 5 * n);
  EXPECT_EQ(validator->getValidMotionCount(), 5 * valid_motions);
  EXPECT_EQ(validator->getInvalidMotionCount(), 5 * (n - valid_motions));
  if (backend == "gpu" && !routed) {
    std::vector<std::uint8_t> verdicts(n);
    checker->check(rows.data(), n, verdicts.data());
    const GpuCheckStats stats = dynamic_cast<GpuChecker&>(*checker).last_stats();
    EXPECT_GT(stats.bv_tests, 0u) << "the GPU did no work";
  }
  for (std::size_t i = 0; i < n; ++i) {
    si->freeState(states[i]);
    si->freeState(ends[i]);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, OmplConcurrentAdapters,
                         ::testing::Values("fcl", "cpu", "gpu", "GpuRouted"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           name[0] = static_cast<char>(std::toupper(name[0]));
                           return name;  // "Fcl", "Cpu", "Gpu": GPU cases match *Gpu*
                         });

}  // namespace
}  // namespace gplanner

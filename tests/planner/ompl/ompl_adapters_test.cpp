// The OMPL adapters: the state space's metric and resolution equal the planner's, the
// validity checker and motion validator agree with OMPL's own discrete validation
// (one state at a time and in batches, from several threads), OMPL's planners solve a
// shipped scene with our checker, and our planners run as OMPL planners.

#include <gtest/gtest.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <atomic>
#include <future>
#include <thread>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/roadmap_planners.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using ompl_adapters::row_to_state;
using ompl_adapters::state_to_row;

Scene load(const std::string& name) {
  return load_scene(testing::project_root() + "/scenes/" + name);
}

class OmplStateSpace : public ::testing::TestWithParam<std::string> {};

TEST_P(OmplStateSpace, SameRowsMetricAndResolution) {
  const Scene scene = load(GetParam());
  const ob::StateSpacePtr space = ompl_adapters::make_state_space(scene);
  space->setup();
  const int w = scene.space.width();
  const ConfigurationMetric metric = make_metric(scene.space, scene.planner);
  EXPECT_NEAR(space->getMaximumExtent(), space_extent(scene.space, metric),
              1e-6 * space_extent(scene.space, metric));
  CpuChecker checker(scene);
  LocalPlanner local(scene, &checker);
  const std::vector<float> q = testing::sample_configurations(scene, 200, 21);
  ob::State* a = space->allocState();
  ob::State* b = space->allocState();
  std::vector<float> back(w);
  for (int i = 0; i + 1 < 200; i += 2) {
    row_to_state(scene, &q[i * w], a);
    row_to_state(scene, &q[(i + 1) * w], b);
    EXPECT_TRUE(space->satisfiesBounds(a));
    state_to_row(scene, a, back.data());
    for (int k = 0; k < w; ++k) EXPECT_NEAR(back[k], q[i * w + k], 1e-6) << k;
    const double ours = distance(metric, &q[i * w], &q[(i + 1) * w]);
    EXPECT_NEAR(space->distance(a, b), ours, 1e-4 * (1 + ours));
    EXPECT_EQ(static_cast<int>(space->validSegmentCount(a, b)),
              local.segments(&q[i * w], &q[(i + 1) * w]));
  }
  space->freeState(a);
  space->freeState(b);
}

INSTANTIATE_TEST_SUITE_P(Scenes, OmplStateSpace,
                         ::testing::ValuesIn(testing::shipped_scene_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return testing::scene_test_name(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(OmplStateSpace);

// A space with our validity checker, and random states of the scene.
struct Fixture {
  explicit Fixture(const std::string& name)
      : scene(load(name)),
        checker(scene),
        si(std::make_shared<ob::SpaceInformation>(ompl_adapters::make_state_space(scene))) {
    validity = std::make_shared<ompl_adapters::StateValidityChecker>(si, scene, &checker);
    si->setStateValidityChecker(validity);
    si->setup();
  }
  std::vector<ob::State*> states(std::size_t n, unsigned seed) {
    const std::vector<float> q = testing::sample_configurations(scene, n, seed);
    std::vector<ob::State*> out;
    for (std::size_t i = 0; i < n; ++i) {
      out.push_back(si->allocState());
      row_to_state(scene, &q[i * scene.space.width()], out.back());
    }
    return out;
  }
  Scene scene;
  CpuChecker checker;
  ob::SpaceInformationPtr si;
  std::shared_ptr<ompl_adapters::StateValidityChecker> validity;
};

TEST(OmplValidityChecker, BatchesAndThreadsGiveTheSameAnswers) {
  Fixture f("pr2_base_arm.yaml");
  const std::vector<ob::State*> states = f.states(400, 3);
  std::vector<std::uint8_t> one(400);
  for (int i = 0; i < 400; ++i) one[i] = f.validity->isValid(states[i]);
  const std::size_t valid = std::count(one.begin(), one.end(), 1);
  EXPECT_GT(valid, 0u);
  EXPECT_LT(valid, 400u);
  std::vector<std::uint8_t> batch;
  f.validity->areValid(std::vector<const ob::State*>(states.begin(), states.end()), &batch);
  EXPECT_EQ(batch, one);
  std::vector<std::future<std::vector<std::uint8_t>>> threads;
  for (int t = 0; t < 4; ++t) {
    threads.push_back(std::async(std::launch::async, [&] {
      std::vector<std::uint8_t> v(400);
      for (int i = 0; i < 400; ++i) v[i] = f.validity->isValid(states[i]);
      return v;
    }));
  }
  for (auto& t : threads) EXPECT_EQ(t.get(), one);
  for (ob::State* s : states) f.si->freeState(s);
}

TEST(OmplMotionValidator, AgreesWithOmplsDiscreteMotionValidator) {
  Fixture f("pr2_base_arm.yaml");
  ompl_adapters::MotionValidator ours(f.si, f.scene, &f.checker, EdgeChecks::kSampled);
  ob::DiscreteMotionValidator discrete(f.si);
  const std::vector<ob::State*> states = f.states(300, 7);
  std::vector<std::pair<const ob::State*, const ob::State*>> motions;
  for (int i = 0; i + 1 < 300; i += 2) {
    if (!f.validity->isValid(states[i])) continue;
    // Shorter motions too: a fifth of the way.
    ob::State* near = f.si->allocState();
    f.si->getStateSpace()->interpolate(states[i], states[i + 1], 0.2, near);
    motions.emplace_back(states[i], near);
    motions.emplace_back(states[i], states[i + 1]);
  }
  ASSERT_GT(motions.size(), 20u);
  ob::State* last_ours = f.si->allocState();
  ob::State* last_omp = f.si->allocState();
  std::size_t valid = 0;
  std::vector<std::uint8_t> singles;
  for (const auto& [a, b] : motions) {
    std::pair<ob::State*, double> lo{last_ours, 0}, lb{last_omp, 0};
    const bool x = ours.checkMotion(a, b, lo);
    const bool y = discrete.checkMotion(a, b, lb);
    EXPECT_EQ(x, y);
    singles.push_back(x);
    if (x) {
      ++valid;
    } else if (!y) {
      EXPECT_NEAR(lo.second, lb.second, 1e-9);
      EXPECT_LT(f.si->distance(last_ours, last_omp), 1e-4);
    }
  }
  EXPECT_GT(valid, 0u);
  EXPECT_LT(valid, motions.size());
  EXPECT_EQ(ours.getValidMotionCount(), valid);
  EXPECT_EQ(ours.getInvalidMotionCount(), motions.size() - valid);
  std::vector<std::uint8_t> batch;
  ours.checkMotions(motions, &batch);
  EXPECT_EQ(batch, singles);
  EXPECT_EQ(ours.getCheckedMotionCount(), 2 * motions.size());
  f.si->freeState(last_ours);
  f.si->freeState(last_omp);
  for (std::size_t i = 0; i < motions.size(); i += 2)
    f.si->freeState(const_cast<ob::State*>(motions[i].second));
  for (ob::State* s : states) f.si->freeState(s);
}

// A checker that counts the configurations it is asked about (a CPU backend's calls).
class CountingChecker : public CollisionChecker {
 public:
  explicit CountingChecker(CollisionChecker* inner) : inner_(inner) {}
  std::string backend() const override { return inner_->backend(); }
  void check(const float* q, std::size_t n, std::uint8_t* verdicts) override {
    checked += n;
    inner_->check(q, n, verdicts);
  }
  void check_clearances(const float* q, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override {
    checked += n;
    inner_->check_clearances(q, n, clearances, verdicts);
  }
  std::atomic<std::size_t> checked{0};

 private:
  CollisionChecker* inner_;
};

// One motion at a time (RRTConnect's calls), as OMPL's DiscreteMotionValidator: the end
// state first, then coarse to fine, up to the first collision; so an invalid motion costs
// about what it costs OMPL's validator, not all its samples.
TEST(OmplMotionValidator, StopsAtTheFirstCollisionAsOmplsDoes) {
  Fixture f("pr2_base_arm.yaml");
  CountingChecker counting(&f.checker);
  const auto counted_si =
      std::make_shared<ob::SpaceInformation>(ompl_adapters::make_state_space(f.scene));
  counted_si->setStateValidityChecker(
      std::make_shared<ompl_adapters::StateValidityChecker>(counted_si, f.scene, &counting));
  counted_si->setup();
  ompl_adapters::MotionValidator ours(counted_si, f.scene, &counting, EdgeChecks::kSampled);
  ob::DiscreteMotionValidator discrete(counted_si);
  LocalPlanner local(f.scene, &f.checker);
  const std::vector<ob::State*> states = f.states(400, 11);
  std::size_t ours_checked = 0, omplds_checked = 0, invalid_samples = 0, invalid_checked = 0;
  std::size_t invalid = 0, valid = 0;
  std::vector<float> a(f.scene.space.width()), b(f.scene.space.width());
  for (int i = 0; i + 1 < 400; ++i) {
    if (!f.validity->isValid(states[i])) continue;
    counting.checked = 0;
    const bool x = ours.checkMotion(states[i], states[i + 1]);
    const std::size_t by_ours = counting.checked;
    counting.checked = 0;
    const bool y = discrete.checkMotion(states[i], states[i + 1]);
    EXPECT_EQ(x, y) << i;
    ours_checked += by_ours;
    omplds_checked += counting.checked;
    state_to_row(f.scene, states[i], a.data());
    state_to_row(f.scene, states[i + 1], b.data());
    if (x) {
      ++valid;
      EXPECT_EQ(by_ours, static_cast<std::size_t>(local.segments(a.data(), b.data())))
          << "a valid motion: every sample and the end";
    } else {
      ++invalid;
      invalid_samples += local.segments(a.data(), b.data());
      invalid_checked += by_ours;
    }
  }
  ASSERT_GT(valid, 5u);
  ASSERT_GT(invalid, 20u);
  EXPECT_LE(ours_checked, omplds_checked + omplds_checked / 4);
  EXPECT_LT(invalid_checked, invalid_samples / 3) << "invalid motions checked nearly whole";
  std::cout << "configurations checked: ours " << ours_checked << ", OMPL's validator "
            << omplds_checked << "; invalid motions: " << invalid_checked << " of "
            << invalid_samples << " samples\n";
  for (ob::State* s : states) f.si->freeState(s);
}

// A resolution the user sets on the space information is followed, as OMPL's own
// validators follow it: four times finer, a valid motion is checked at four times the
// samples, as many as OMPL's DiscreteMotionValidator checks.
TEST(OmplMotionValidator, FollowsTheResolutionSetOnTheSpaceInformation) {
  Fixture f("piano.yaml");
  CountingChecker counting(&f.checker);
  const auto si = std::make_shared<ob::SpaceInformation>(ompl_adapters::make_state_space(f.scene));
  si->setStateValidityChecker(
      std::make_shared<ompl_adapters::StateValidityChecker>(si, f.scene, &counting));
  const double scene_resolution = si->getStateValidityCheckingResolution();
  si->setStateValidityCheckingResolution(scene_resolution / 4);
  si->setup();
  ompl_adapters::MotionValidator ours(si, f.scene, &counting, EdgeChecks::kSampled);
  ob::DiscreteMotionValidator discrete(si);
  LocalPlanner at_scene_resolution(f.scene, &f.checker);
  const std::vector<ob::State*> states = f.states(200, 5);
  std::vector<float> a(f.scene.space.width()), b(f.scene.space.width());
  int compared = 0;
  for (int i = 0; i + 1 < 200 && compared < 10; ++i) {
    ob::State* near = si->allocState();
    si->getStateSpace()->interpolate(states[i], states[i + 1], 0.05, near);
    counting.checked = 0;
    const bool x = ours.checkMotion(states[i], near);
    const std::size_t by_ours = counting.checked;
    counting.checked = 0;
    const bool y = discrete.checkMotion(states[i], near);
    EXPECT_EQ(x, y) << i;
    if (x && f.validity->isValid(states[i])) {
      state_to_row(f.scene, states[i], a.data());
      state_to_row(f.scene, near, b.data());
      EXPECT_EQ(by_ours, counting.checked) << i;  // every sample and the end, both
      EXPECT_GE(by_ours, 3u * at_scene_resolution.segments(a.data(), b.data())) << i;
      ++compared;
    }
    si->freeState(near);
  }
  EXPECT_GT(compared, 3);
  for (ob::State* s : states) f.si->freeState(s);
}

// Certified: every answer is CertifiedMotions's, one motion at a time and in a batch; a
// motion that is not certified has a last valid state up to which it certifies.
TEST(OmplMotionValidator, CertifiedAnswersAreCertifiedMotions) {
  Fixture f("piano.yaml");
  const ompl_adapters::MotionValidator validator(f.si, f.scene, &f.checker, EdgeChecks::kCertified);
  CertifiedMotions certified(f.scene, &f.checker);
  const std::size_t n = 40, w = f.scene.space.width();
  // Motions from valid states (OMPL's validators assume the start valid).
  std::vector<ob::State*> states;
  for (ob::State* s : f.states(20 * n, 41)) {
    if (states.size() < 2 * n && (states.size() % 2 == 1 || f.si->isValid(s))) {
      states.push_back(s);
    } else {
      f.si->freeState(s);
    }
  }
  ASSERT_EQ(states.size(), 2 * n);
  std::vector<std::pair<const ob::State*, const ob::State*>> motions;
  std::vector<float> from(n * w), to(n * w), end(w);
  for (std::size_t i = 0; i < n; ++i) {
    // A tenth of the way toward another state: a roadmap edge's length.
    f.si->getStateSpace()->interpolate(states[2 * i], states[2 * i + 1], 0.1, states[2 * i + 1]);
    motions.emplace_back(states[2 * i], states[2 * i + 1]);
    state_to_row(f.scene, states[2 * i], &from[i * w]);
    state_to_row(f.scene, states[2 * i + 1], &to[i * w]);
  }
  std::vector<std::uint8_t> invalid(n);
  ASSERT_TRUE(certified.check_motions(from.data(), to.data(), n, invalid.data()));
  std::vector<std::uint8_t> batch;
  validator.checkMotions(motions, &batch);
  ob::State* last = f.si->allocState();
  std::size_t valid = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::pair<ob::State*, double> last_valid{last, -1.0};
    const bool ok = validator.checkMotion(motions[i].first, motions[i].second, last_valid);
    EXPECT_EQ(ok, invalid[i] == 0) << i;
    EXPECT_EQ(batch[i], invalid[i] == 0 ? 1 : 0) << i;
    valid += ok;
    if (ok) continue;
    ASSERT_GE(last_valid.second, 0.0);
    ASSERT_LT(last_valid.second, 1.0);
    state_to_row(f.scene, last, end.data());
    std::uint8_t prefix = 1;
    ASSERT_TRUE(certified.check_motions(&from[i * w], end.data(), 1, &prefix));
    EXPECT_EQ(prefix, 0) << i << ": the motion up to its last valid state is certified";
  }
  EXPECT_GT(valid, 0u);
  EXPECT_LT(valid, n) << "no invalid motion: the last valid states were not tested";
  f.si->freeState(last);
  for (ob::State* s : states) f.si->freeState(s);
}

// SimpleSetup for a scene with our checker and motion validator.
std::unique_ptr<og::SimpleSetup> setup_for(Fixture* f) {
  auto setup = std::make_unique<og::SimpleSetup>(f->si);
  f->si->setMotionValidator(
      std::make_shared<ompl_adapters::MotionValidator>(f->si, f->scene, &f->checker));
  ob::ScopedState<> start(f->si), goal(f->si);
  row_to_state(f->scene, f->scene.start.data(), start.get());
  row_to_state(f->scene, f->scene.goal.data(), goal.get());
  setup->setStartAndGoalStates(start, goal);
  return setup;
}

std::vector<float> solution_rows(const Scene& scene, og::SimpleSetup* setup) {
  const og::PathGeometric& path = setup->getSolutionPath();
  std::vector<float> rows(path.getStateCount() * scene.space.width());
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    state_to_row(scene, path.getState(i), &rows[i * scene.space.width()]);
  return rows;
}

// OMPL's planners are seeded (OMPL's global seed, before any of its generators exists),
// so that each test, run in its own process as CTest runs them, repeats exactly.
class OmplSeed : public ::testing::Environment {
 public:
  void SetUp() override {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ompl::RNG::setSeed(7);
  }
};
const auto* const kOmplSeed = ::testing::AddGlobalTestEnvironment(new OmplSeed);

template <typename OmplPlanner>
void expect_solves_with_our_checker(const std::string& name) {
  Fixture f(name);
  auto setup = setup_for(&f);
  setup->setPlanner(std::make_shared<OmplPlanner>(f.si));
  ASSERT_EQ(setup->solve(120.0), ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_GT(f.validity->checks(), 0u);
  EXPECT_GT(f.si->getMotionValidator()->getCheckedMotionCount(), 0u);
  EXPECT_EQ(testing::path_problem(f.scene, solution_rows(f.scene, setup.get())), "");
}

TEST(OmplPlanners, RrtConnectSolvesAShippedSceneWithOurChecker) {
  expect_solves_with_our_checker<og::RRTConnect>("pr2_base_arm.yaml");
}

TEST(OmplPlanners, LazyPrmSolvesAShippedSceneWithOurChecker) {
  expect_solves_with_our_checker<og::LazyPRM>("pr2_base_arm.yaml");
}

TEST(OmplPlanners, OurPlannersRunAsOmplPlanners) {
  for (const bool lazy : {true, false}) {
    Fixture f("pr2_base_arm.yaml");
    auto setup = setup_for(&f);
    std::shared_ptr<ompl_adapters::RoadmapOmplPlanner> planner;
    if (lazy) {
      planner = std::make_shared<ompl_adapters::LazyPrm>(f.si, f.scene, &f.checker);
    } else {
      planner = std::make_shared<ompl_adapters::Prm>(f.si, f.scene, &f.checker);
    }
    planner->options().milestones = 250;
    setup->setPlanner(planner);
    ASSERT_EQ(setup->solve(120.0), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(testing::path_problem(f.scene, solution_rows(f.scene, setup.get())), "");
    ob::PlannerData data(f.si);
    setup->getPlannerData(data);
    EXPECT_EQ(data.numVertices(), planner->last_result().milestones);
    EXPECT_GT(data.numEdges(), 0u);
    const auto& properties = planner->getPlannerProgressProperties();
    ASSERT_EQ(properties.count("milestone count INTEGER"), 1u);
    EXPECT_EQ(properties.at("milestone count INTEGER")(),
              std::to_string(planner->last_result().milestones));
  }
}

TEST(OmplPlanners, OurPlannerStopsWhenTold) {
  Fixture f("piano.yaml");
  auto setup = setup_for(&f);
  auto planner = std::make_shared<ompl_adapters::LazyPrm>(f.si, f.scene, &f.checker);
  planner->options().milestones = 50;  // far too few: the roadmap must grow
  setup->setPlanner(planner);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(setup->solve(0.2), ob::PlannerStatus::TIMEOUT);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);
  EXPECT_EQ(planner->last_result().stop_reason, "stopped");
}

}  // namespace
}  // namespace gplanner

// Our planners follow OMPL's conventions: seeded from ompl::RNG (runs differ, OMPL's
// global seed repeats them, an explicit seed is kept), declared parameters that change
// what they do, OMPL's PRM's progress property names, messages through OMPL's console
// (the gpu backend's CPU fallback included), the time limit kept, motions sampled at
// the space information's resolution and counted in its motion validator.

#include <gtest/gtest.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/ompl/checker_factory.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/roadmap_planners.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace ob = ompl::base;
using ompl_adapters::LazyPrm;
using ompl_adapters::Prm;
using ompl_adapters::RoadmapOmplPlanner;

// A scene with our validity checker and motion validator, and a problem from its start
// to its goal.
struct Problem {
  explicit Problem(const std::string& name)
      : scene(load_scene(testing::project_root() + "/scenes/" + name)),
        checker(scene),
        si(std::make_shared<ob::SpaceInformation>(ompl_adapters::make_state_space(scene))) {
    si->setStateValidityChecker(
        std::make_shared<ompl_adapters::StateValidityChecker>(si, scene, &checker));
    si->setMotionValidator(std::make_shared<ompl_adapters::MotionValidator>(si, scene, &checker));
    si->setup();
    pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<> start(si), goal(si);
    ompl_adapters::row_to_state(scene, scene.start.data(), start.get());
    ompl_adapters::row_to_state(scene, scene.goal.data(), goal.get());
    pdef->setStartAndGoalStates(start, goal);
  }
  template <typename Planner>
  std::shared_ptr<Planner> planner(const std::map<std::string, std::string>& params = {}) {
    auto p = std::make_shared<Planner>(si, scene, &checker);
    p->setProblemDefinition(pdef);
    EXPECT_TRUE(p->params().setParams(params));
    p->setup();
    return p;
  }
  Scene scene;
  CpuChecker checker;
  ob::SpaceInformationPtr si;
  ob::ProblemDefinitionPtr pdef;
};

const std::map<std::string, std::string> kSmall = {{"milestones", "250"}};

// Collects OMPL's console messages while it lives (at `level` and above).
class ConsoleCapture : public ompl::msg::OutputHandler {
 public:
  explicit ConsoleCapture(ompl::msg::LogLevel level) : level_(ompl::msg::getLogLevel()) {
    ompl::msg::useOutputHandler(this);
    ompl::msg::setLogLevel(level);
  }
  ~ConsoleCapture() override {
    ompl::msg::restorePreviousOutputHandler();
    ompl::msg::setLogLevel(level_);
  }
  void log(const std::string& text, ompl::msg::LogLevel level, const char*, int) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    messages_.emplace_back(level, text);
  }
  // The messages at `level` containing `part`.
  std::size_t count(ompl::msg::LogLevel level, const std::string& part) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::size_t n = 0;
    for (const auto& [l, text] : messages_) n += l == level && text.find(part) != std::string::npos;
    return n;
  }

 private:
  ompl::msg::LogLevel level_;
  mutable std::mutex mutex_;
  std::vector<std::pair<ompl::msg::LogLevel, std::string>> messages_;
};

// The path of a lazy PRM made (with its problem) after ompl::RNG::setSeed(seed), and
// the roadmap's seed.
std::pair<std::vector<float>, unsigned long long> plan_after_global_seed(std::uint32_t seed) {
  const ConsoleCapture quiet(ompl::msg::LOG_NONE);  // OMPL objects already drew seeds: it says so
  ompl::RNG::setSeed(seed);
  Problem p("pr2_base_arm.yaml");
  auto planner = p.planner<LazyPrm>(kSmall);
  EXPECT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  return {planner->last_result().path, planner->roadmap_seed()};
}

TEST(OmplConventions, SeededFromOmplsRandomNumbers) {
  const auto a = plan_after_global_seed(11);
  const auto b = plan_after_global_seed(11);
  const auto c = plan_after_global_seed(12);
  EXPECT_NE(a.second, 0u);
  EXPECT_EQ(a.second, b.second) << "OMPL's global seed repeats the roadmap's";
  EXPECT_EQ(a.first, b.first) << "the same seed, the same path";
  EXPECT_NE(a.second, c.second);
  EXPECT_NE(a.first, c.first) << "another seed, another path";
}

TEST(OmplConventions, RunsAfterClearDifferAndAnExplicitSeedIsKept) {
  Problem p("pr2_base_arm.yaml");
  auto planner = p.planner<LazyPrm>(kSmall);
  ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  const unsigned long long first_seed = planner->roadmap_seed();
  const std::vector<float> first = planner->last_result().path;
  // Without clear(): the same roadmap answers again.
  p.pdef->clearSolutionPaths();
  ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_EQ(planner->roadmap_seed(), first_seed);
  EXPECT_EQ(planner->last_result().rounds, 1u);
  // As Benchmark runs them: clear() between runs.
  planner->clear();
  p.pdef->clearSolutionPaths();
  ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_NE(planner->roadmap_seed(), first_seed);
  EXPECT_NE(planner->last_result().path, first);
  // An explicit seed: used as is, run after run.
  std::vector<float> explicit_path;
  for (int run = 0; run < 2; ++run) {
    planner->clear();
    p.pdef->clearSolutionPaths();
    ASSERT_TRUE(planner->params().setParam("seed", "12345"));
    ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
    EXPECT_EQ(planner->roadmap_seed(), 12345u);
    if (run == 0) explicit_path = planner->last_result().path;
  }
  EXPECT_EQ(planner->last_result().path, explicit_path);
}

TEST(OmplConventions, DeclaredParametersChangeThePlanner) {
  Problem p("pr2_base_arm.yaml");
  for (const bool lazy : {false, true}) {
    std::shared_ptr<RoadmapOmplPlanner> planner;
    if (lazy) {
      planner = p.planner<LazyPrm>();
    } else {
      planner = p.planner<Prm>();
    }
    std::map<std::string, std::string> values;
    planner->params().getParams(values);
    for (const char* name : {"milestones", "max_nearest_neighbors", "shortcut_rounds",
                             "certified_edges", "certify_path", "seed"}) {
      ASSERT_EQ(values.count(name), 1u) << name;
      EXPECT_FALSE(values[name].empty()) << name << ": Benchmark logs the value";
    }
    EXPECT_EQ(values.count("lazy_batch_paths"), lazy ? 1u : 0u);
    EXPECT_FALSE(planner->params()["milestones"].getRangeSuggestion().empty());
    EXPECT_FALSE(planner->params().setParam("milestones", "many"));

    ASSERT_TRUE(planner->params().setParams({{"milestones", "123"},
                                             {"max_nearest_neighbors", "3"},
                                             {"shortcut_rounds", "0"},
                                             {"certified_edges", "1"},
                                             {"certify_path", "0"},
                                             {"seed", "99"}}));
    EXPECT_EQ(planner->options().milestones, 123u);
    EXPECT_EQ(planner->options().neighbors, 3);
    EXPECT_EQ(planner->options().shortcut_rounds, 0);
    EXPECT_EQ(planner->options().edges, EdgeChecks::kCertified);
    EXPECT_FALSE(planner->options().certify_path);
    EXPECT_EQ(planner->options().seed, 99u);
    if (lazy) {
      ASSERT_TRUE(planner->params().setParam("lazy_batch_paths", "3"));
      EXPECT_EQ(planner->options().lazy_batch_paths, 3);
    }
    planner->params().getParams(values);
    EXPECT_EQ(values["milestones"], "123");
    EXPECT_EQ(values["certified_edges"], "1");

    // What the planner does: the first round's milestones, at most k edges a milestone
    // (k = 15 gives about 9); solved or not.
    ASSERT_TRUE(planner->params().setParam("certified_edges", "0"));
    planner->solve(3.0);
    const PlanResult& r = planner->last_result();
    EXPECT_GE(r.milestones, 123u + 2);
    EXPECT_LE(r.edges, 3 * r.milestones);
    planner->clear();
    p.pdef->clearSolutionPaths();
  }
  // Shortcutting off and on, from the same seed.
  double length[2] = {0, 0};
  for (const bool shortcut : {false, true}) {
    auto planner = p.planner<LazyPrm>({{"milestones", "250"}, {"seed", "5"}});
    if (!shortcut) ASSERT_TRUE(planner->params().setParam("shortcut_rounds", "0"));
    ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
    const PlanResult& r = planner->last_result();
    if (!shortcut) EXPECT_EQ(r.length, r.length_before_shortcut);
    length[shortcut] = r.length;
    p.pdef->clearSolutionPaths();
  }
  EXPECT_LT(length[1], length[0]);
}

TEST(OmplConventions, ProgressPropertiesAsOmplsPrmNamesThem) {
  Problem p("pr2_base_arm.yaml");
  auto planner = p.planner<Prm>(kSmall);
  const auto& properties = planner->getPlannerProgressProperties();
  for (const char* name : {"iterations INTEGER", "best cost REAL", "milestone count INTEGER",
                           "edge count INTEGER", "valid edge count INTEGER", "seed INTEGER"}) {
    ASSERT_EQ(properties.count(name), 1u) << name;
  }
  ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  const PlanResult& r = planner->last_result();
  EXPECT_EQ(properties.at("iterations INTEGER")(), std::to_string(r.rounds));
  EXPECT_EQ(properties.at("milestone count INTEGER")(), std::to_string(r.milestones));
  EXPECT_EQ(properties.at("edge count INTEGER")(), std::to_string(r.edges));
  EXPECT_NEAR(std::stod(properties.at("best cost REAL")()), r.length, 1e-4 * r.length);
  EXPECT_GT(std::stoul(properties.at("valid edge count INTEGER")()), 0u);
  EXPECT_EQ(properties.at("seed INTEGER")(), std::to_string(planner->roadmap_seed()));
}

TEST(OmplConventions, MessagesThroughOmplsConsole) {
  Problem p("pr2_base_arm.yaml");
  auto planner = p.planner<LazyPrm>(kSmall);
  const ConsoleCapture console(ompl::msg::LOG_INFO);
  ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  EXPECT_EQ(console.count(ompl::msg::LOG_INFO, "gplanner LazyPRM: Starting planning with"), 1u);
  EXPECT_EQ(console.count(ompl::msg::LOG_INFO, "gplanner LazyPRM: Created "), 1u);
}

TEST(OmplConventions, GpuBackendOnTheCpuIsAnOmplWarning) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/piano.yaml");
  const GpuDevice device = query_gpu_device();
  const ConsoleCapture console(ompl::msg::LOG_WARN);
  const auto cpu = ompl_adapters::make_collision_checker(scene, "cpu");
  EXPECT_EQ(console.count(ompl::msg::LOG_WARN, "gplanner:"), 0u);
  const auto gpu = ompl_adapters::make_collision_checker(scene, "gpu");
  if (device.available) {
    EXPECT_EQ(gpu->backend(), "gpu");
    EXPECT_EQ(console.count(ompl::msg::LOG_WARN, "gplanner:"), 0u);
  } else {
    EXPECT_EQ(gpu->backend(), "cpu");
    EXPECT_EQ(console.count(ompl::msg::LOG_WARN, "the cpu backend runs instead"), 1u);
  }
  EXPECT_THROW(ompl_adapters::make_collision_checker(scene, "abacus"), std::invalid_argument);
}

// A hard problem (the piano through its doorways from 50 milestones) stopped at 0.2 s:
// the planner returns within the limit and a small margin (OMPL's termination condition
// polled between short slices of every stage).
TEST(OmplConventions, TimeLimitKept) {
  Problem p("piano.yaml");
  for (const bool lazy : {true, false}) {
    std::shared_ptr<RoadmapOmplPlanner> planner;
    if (lazy) {
      planner = p.planner<LazyPrm>({{"milestones", "50"}});
    } else {
      planner = p.planner<Prm>({{"milestones", "50"}});
    }
    const auto start = std::chrono::steady_clock::now();
    const ob::PlannerStatus status = planner->solve(0.2);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(status, ob::PlannerStatus::TIMEOUT);
    EXPECT_LT(seconds, 0.2 + 0.1) << (lazy ? "lazy PRM" : "PRM");
    EXPECT_EQ(planner->last_result().stop_reason, "stopped");
  }
}

// Our planners sample motions as OMPL's validators do (the space information's
// resolution), and count the edges they checked in its motion validator (Benchmark's
// "valid segment fraction").
TEST(OmplConventions, ResolutionAndMotionCountsAsOmpls) {
  Problem p("pr2_base_arm.yaml");
  EXPECT_DOUBLE_EQ(p.si->getStateValidityCheckingResolution(), p.scene.planner.edge_resolution);
  auto planner = p.planner<Prm>(kSmall);
  EXPECT_DOUBLE_EQ(planner->options().local.resolution_fraction,
                   p.si->getStateValidityCheckingResolution());
  p.si->getMotionValidator()->resetMotionCounter();
  ASSERT_EQ(planner->solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
  const ob::MotionValidatorPtr& validator = p.si->getMotionValidator();
  EXPECT_GT(validator->getValidMotionCount(), 0u);
  EXPECT_GT(validator->getInvalidMotionCount(), 0u);
  EXPECT_GT(validator->getValidMotionFraction(), 0.0);
  EXPECT_LT(validator->getValidMotionFraction(), 1.0);

  // A resolution set on the space information is the planner's.
  p.si->setStateValidityCheckingResolution(0.005);
  auto finer = std::make_shared<Prm>(p.si, p.scene, &p.checker);
  finer->setup();
  EXPECT_DOUBLE_EQ(finer->options().local.resolution_fraction, 0.005);
}

}  // namespace
}  // namespace gplanner

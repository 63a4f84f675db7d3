// Planner settings (planner/src/scene/planner_settings.cpp): the built-in defaults are
// config/planner.yaml's, a scene's `planner:` overrides them member by member, and every
// value outside its range is refused naming the scene file, its line and the key, before
// anything is set (a fraction is no whole number, a negative count no huge one).

#include "gplanner/planner/scene/planner_settings.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <string>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::ScratchFolder;

std::string config_file() { return testing::project_root() + "/config/planner.yaml"; }

Scene load_with(const ScratchFolder& folder, const std::string& planner) {
  folder.write("cube.obj", testing::kCubeObj);
  return load_scene(
      folder.write("scene.yaml", std::string(testing::kCubeAndThinWallScene) + planner));
}

TEST(PlannerSettings, DefaultsAreThoseOfConfigPlannerYaml) {
  const YAML::Node file = YAML::LoadFile(config_file());
  const PlannerSettings s;
  EXPECT_EQ(s.seed, file["seed"].as<std::uint64_t>());
  EXPECT_EQ(s.time_limit_s, file["time_limit_s"].as<double>());
  EXPECT_EQ(s.distance_weights.position, file["distance_weights"]["position"].as<double>());
  EXPECT_EQ(s.distance_weights.rotation, file["distance_weights"]["rotation"].as<double>());
  EXPECT_EQ(s.distance_weights.joint, file["distance_weights"]["joint"].as<double>());
  EXPECT_EQ(s.delta_fraction, file["delta_fraction"].as<double>());
  EXPECT_EQ(s.edge_resolution, file["edge_resolution"].as<double>());
  EXPECT_EQ(s.max_displacement, file["max_displacement"].as<double>());
  EXPECT_EQ(s.roadmap.milestones, file["roadmap"]["milestones"].as<std::size_t>());
  EXPECT_EQ(s.roadmap.neighbors, file["roadmap"]["neighbors"].as<int>());
  EXPECT_EQ(s.roadmap.lazy_batch_paths, file["roadmap"]["lazy_batch_paths"].as<int>());
  EXPECT_EQ(s.shortcut.rounds, file["shortcut"]["rounds"].as<int>());
  EXPECT_EQ(s.shortcut.candidates, file["shortcut"]["candidates"].as<int>());
  EXPECT_EQ(s.sampler.rotation_spread, file["sampler"]["rotation_spread"].as<double>());
  EXPECT_EQ(s.sampler.bridge_fraction, file["sampler"]["bridge_fraction"].as<double>());
  EXPECT_EQ(s.sampler.bridge_sigma, file["sampler"]["bridge_sigma"].as<double>());
  // A scene without `planner:` has them too.
  const ScratchFolder folder;
  const Scene scene = load_with(folder, "");
  EXPECT_EQ(scene.planner.roadmap.milestones, s.roadmap.milestones);
  EXPECT_EQ(scene.planner.edge_resolution, s.edge_resolution);
}

TEST(PlannerSettings, AScenesOverridesSetTheirMembersAndNoOthers) {
  const ScratchFolder folder;
  const Scene scene = load_with(folder,
                                "planner:\n"
                                "  seed: 9007199254740992\n"
                                "  roadmap: {milestones: 123, neighbors: 7}\n"
                                "  distance_weights: {rotation: 0.5}\n"
                                "  sampler: {bridge_fraction: 0.25}\n");
  const PlannerSettings defaults;
  EXPECT_EQ(scene.planner.seed, 9007199254740992ull);
  EXPECT_EQ(scene.planner.roadmap.milestones, 123u);
  EXPECT_EQ(scene.planner.roadmap.neighbors, 7);
  EXPECT_EQ(scene.planner.roadmap.lazy_batch_paths, defaults.roadmap.lazy_batch_paths);
  EXPECT_EQ(scene.planner.distance_weights.rotation, 0.5);
  EXPECT_EQ(scene.planner.distance_weights.position, defaults.distance_weights.position);
  EXPECT_EQ(scene.planner.sampler.bridge_fraction, 0.25);
  EXPECT_EQ(scene.planner.time_limit_s, defaults.time_limit_s);
}

TEST(PlannerSettings, TheDeprecatedLookupByKeyReadsTheMembers) {
  const ScratchFolder folder;
  const Scene scene = load_with(folder, "planner:\n  roadmap: {milestones: 77}\n");
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  EXPECT_EQ(scene.planner.number("roadmap.milestones"), 77);
  EXPECT_EQ(scene.planner.number("edge_resolution"), scene.planner.edge_resolution);
  EXPECT_THROW(scene.planner.number("roadmap"), std::out_of_range);
#pragma GCC diagnostic pop
}

// The message of the InputError that loading throws, or "" when it loads.
std::string refusal(const std::string& planner) {
  const ScratchFolder folder;
  try {
    load_with(folder, planner);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PlannerSettings, ValuesOutsideTheirRangesAreRefusedWithTheLineAndKey) {
  struct Case {
    const char* planner;
    const char* says;
  };
  const Case cases[] = {
      {"planner:\n  seed: 0.5\n", "scene.yaml:14: planner.seed: must be a whole number"},
      {"planner:\n  seed: -1\n", "scene.yaml:14: planner.seed: must be a whole number"},
      {"planner:\n  seed: 9007199254740993.5\n", "planner.seed: must be a whole number"},
      {"planner:\n  roadmap:\n    milestones: 0\n",
       "scene.yaml:15: planner.roadmap.milestones: must be a whole number from 1 to 1e8"},
      {"planner:\n  roadmap: {neighbors: 2.5}\n", "planner.roadmap.neighbors: must be a whole"},
      {"planner:\n  shortcut: {rounds: -3}\n", "planner.shortcut.rounds: must be a whole"},
      {"planner:\n  time_limit_s: 0\n", "planner.time_limit_s: must be a positive number"},
      {"planner:\n  delta_fraction: 2.0e-5\n", "planner.delta_fraction: must lie in (0, 1e-5]"},
      {"planner:\n  edge_resolution: 0\n", "planner.edge_resolution: must lie in [1e-5, 1]"},
      {"planner:\n  sampler: {bridge_fraction: 1.5}\n", "planner.sampler.bridge_fraction"},
      {"planner:\n  sampler: {bridge_sigma: 0}\n",
       "planner.sampler.bridge_sigma: must be a positive"},
      {"planner:\n  distance_weights: {joint: -1}\n", "planner.distance_weights.joint: must be 0"},
      {"planner:\n  roadmap: {size: 3}\n", "planner.roadmap.size: unknown planner setting"},
      {"planner:\n  roadmap: 3\n", "planner.roadmap: unknown planner setting"},
      {"planner:\n  seed: [1]\n", "planner.seed: expected a number"},
      {"planner: 3\n", "planner: expected a map of settings"},
      // The weights the cube's floating base uses all 0 (issue 32: it ran to the limit).
      {"planner:\n  distance_weights: {position: 0, rotation: 0}\n",
       "scene.yaml:14: planner.distance_weights: the weights this robot's configurations use "
       "(position, rotation) are all 0"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.planner);
    EXPECT_NE(message.find(c.says), std::string::npos) << c.planner << " gave: " << message;
  }
}

}  // namespace
}  // namespace gplanner

// The --json lines of `gplan plan` and `gplan check` (apps/plan_report, apps/check_report):
// parsed as JSON, every field there in its order with its type, the values agreeing
// with the text report above them. Scripts read these fields: a change is an API change
// (CHANGELOG.md).

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace gplanner {
namespace {

using testing::CommandResult;
using testing::run_gplan;
using testing::ScratchFolder;
using Json = nlohmann::ordered_json;

// The last line of the output, parsed.
Json last_json_line(const std::string& output) {
  std::istringstream in(output);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty() && line[0] == '{') last = line;
  return Json::parse(last);  // throws (and fails the test) when there is none
}

std::vector<std::string> keys(const Json& object) {
  std::vector<std::string> names;
  for (const auto& item : object.items()) names.push_back(item.key());
  return names;
}

std::string thin_wall_scene(const ScratchFolder& folder) {
  folder.write("cube.obj", testing::kCubeObj);
  return folder.write("scene.yaml", std::string(testing::kCubeAndThinWallScene) +
                                        "planner:\n  roadmap: {milestones: 300}\n");
}

TEST(GplanJson, PlanReportsEveryFieldInOrder) {
  const std::string scene = testing::project_root() + "/scenes/piano.yaml";
  const CommandResult run =
      run_gplan("plan '" + scene + "' --backend cpu --seed 3 --time-limit 600 --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Json j = last_json_line(run.output);
  EXPECT_EQ(keys(j), (std::vector<std::string>{"scene",
                                               "name",
                                               "planner",
                                               "planner_asked",
                                               "planner_reason",
                                               "backend",
                                               "knn",
                                               "edge_checks",
                                               "path_check",
                                               "seed",
                                               "solved",
                                               "stop_reason",
                                               "length",
                                               "length_before_shortcut",
                                               "waypoints",
                                               "milestones",
                                               "edges",
                                               "edges_checked",
                                               "states_checked",
                                               "samples_checked",
                                               "searches",
                                               "edge_batches",
                                               "rounds",
                                               "seconds",
                                               "setup_seconds",
                                               "times",
                                               "gpu_calls"}));
  EXPECT_EQ(keys(j["times"]), (std::vector<std::string>{"sampling", "state_checks", "knn", "search",
                                                        "edge_checks", "shortcutting"}));
  EXPECT_EQ(keys(j["gpu_calls"]),
            (std::vector<std::string>{"state_checks", "knn", "search", "edge_checks",
                                      "shortcutting", "total"}));
  EXPECT_EQ(j["gpu_calls"]["total"], 0u);  // the cpu backend makes none
  EXPECT_EQ(j["scene"], scene);
  EXPECT_EQ(j["name"], "piano");
  // auto (the default): lazy PRM for the piano, a rigid body.
  EXPECT_EQ(j["planner"], "lazyprm");
  EXPECT_EQ(j["planner_asked"], "auto");
  EXPECT_EQ(j["planner_reason"], "a rigid body flying free");
  EXPECT_EQ(j["backend"], "cpu");
  EXPECT_EQ(j["edge_checks"], "sampled");
  EXPECT_EQ(j["path_check"], "certified");
  EXPECT_EQ(j["seed"], 3u);
  EXPECT_EQ(j["solved"], true);
  EXPECT_EQ(j["stop_reason"], "solved");
  EXPECT_TRUE(j["edges"].is_number_unsigned());
  EXPECT_GE(j["milestones"].get<int>(), 2002);  // the first round's, start and goal
  EXPECT_GE(j["waypoints"].get<int>(), 2);
  EXPECT_GT(j["length"].get<double>(), 0);
  EXPECT_LE(j["length"].get<double>(), j["length_before_shortcut"].get<double>() + 1e-9);
  EXPECT_GE(j["seconds"].get<double>(), 0);
  // The text report above says the same.
  EXPECT_NE(run.output.find("planner     lazyprm (auto: a rigid body flying free), seed 3, cpu "
                            "backend"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find(std::to_string(j["milestones"].get<int>()) + " milestones"),
            std::string::npos)
      << run.output;
}

TEST(GplanJson, CheckReportsEveryFieldInOrderWithACompare) {
  const ScratchFolder folder;
  const std::string scene = thin_wall_scene(folder);
  const CommandResult run =
      run_gplan("check '" + scene + "' --n 500 --seed 2 --backend cpu --compare fcl --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Json j = last_json_line(run.output);
  EXPECT_EQ(keys(j), (std::vector<std::string>{"scene",
                                               "name",
                                               "backend",
                                               "n",
                                               "seed",
                                               "dof",
                                               "width",
                                               "links",
                                               "robot_triangles",
                                               "checked_pairs",
                                               "obstacle_triangles",
                                               "dropped_obstacle_triangles",
                                               "delta",
                                               "collisions",
                                               "collision_fraction",
                                               "seconds",
                                               "repeat",
                                               "queries_per_second",
                                               "straight_line_collides",
                                               "compare"}));
  EXPECT_EQ(keys(j["compare"]),
            (std::vector<std::string>{"backend", "seconds", "disagreements", "missed_collisions",
                                      "extra_within_band", "extra_outside_band"}));
  EXPECT_EQ(j["n"], 500u);
  EXPECT_EQ(j["seed"], 2u);
  EXPECT_EQ(j["dof"], 6);
  EXPECT_EQ(j["width"], 7u);
  EXPECT_EQ(j["links"], 1u);
  EXPECT_EQ(j["robot_triangles"], 12u);
  EXPECT_EQ(j["straight_line_collides"], true);  // the wall lies across the way
  EXPECT_EQ(j["compare"]["backend"], "fcl");
  EXPECT_EQ(j["compare"]["missed_collisions"], 0u);
  const double fraction = j["collision_fraction"].get<double>();
  EXPECT_DOUBLE_EQ(fraction, j["collisions"].get<double>() / 500);
  EXPECT_NE(run.output.find("checked     500 configurations (seed 2)"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("collisions  " + std::to_string(j["collisions"].get<int>()) + " ("),
            std::string::npos)
      << run.output;
}

TEST(GplanJson, NamesThatAreNotUtf8ComeOutAsReplacementCharacters) {
  const ScratchFolder folder;
  folder.write("cube.obj", testing::kCubeObj);
  std::string text = testing::kCubeAndThinWallScene;
  text.replace(text.find("name: thin_wall"), 15, "name: wall \xff\xfe");  // not UTF-8
  const std::string scene = folder.write("scene.yaml", text);
  const CommandResult run = run_gplan("check '" + scene + "' --n 10 --backend cpu --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Json j = last_json_line(run.output);
  EXPECT_EQ(j["name"], "wall \xef\xbf\xbd\xef\xbf\xbd");  // U+FFFD twice
}

}  // namespace
}  // namespace gplanner

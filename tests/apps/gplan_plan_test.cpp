// `gplan plan` through the real binary: every shipped scene planned with lazy PRM (on
// the cpu backend here, on the GPU in the *Gpu* cases), the path file read back and
// re-checked by FCL at a tenth of the edge resolution; usage errors, no path within
// the limit, and roadmap files.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/planning/path_recheck.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::CommandResult;
using testing::run_gplan;
using testing::ScratchFolder;

std::string scene_path(const std::string& file) {
  return testing::project_root() + "/scenes/" + file;
}

// The configurations of a path file.
std::vector<float> read_path(const std::string& file, int width) {
  const YAML::Node root = YAML::LoadFile(file);
  std::vector<float> path;
  for (const YAML::Node& waypoint : root["waypoints"]) {
    const YAML::Node q = waypoint["configuration"];
    EXPECT_EQ(static_cast<int>(q.size()), width);
    for (const YAML::Node& v : q) path.push_back(v.as<float>());
    EXPECT_TRUE(waypoint["base"]["position"]) << file;
    EXPECT_TRUE(waypoint["base"]["quat_wxyz"]) << file;
  }
  return path;
}

std::string json_text(const std::string& output, const std::string& key) {
  std::smatch m;
  if (std::regex_search(output, m, std::regex("\"" + key + "\":\"([^\"]*)\""))) return m[1];
  return "";
}

void expect_plans(const std::string& file, const std::string& backend) {
  const Scene scene = load_scene(scene_path(file));
  ScratchFolder scratch;
  const std::string out = scratch.path() + "/path.yaml";
  const CommandResult run = run_gplan("plan '" + scene_path(file) + "' --backend " + backend +
                                      " --time-limit 600 --json --out '" + out + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("\"solved\":true"), std::string::npos) << run.output;
  EXPECT_EQ(json_text(run.output, "backend"), backend) << run.output;
  EXPECT_EQ(json_text(run.output, "knn"), backend) << run.output;
  EXPECT_NE(run.output.find("time        "), std::string::npos) << run.output;
  const std::vector<float> path = read_path(out, scene.space.width());
  EXPECT_EQ(testing::path_problem(scene, path), "") << run.output;
  std::cout << file << " (" << backend << "): " << run.output.substr(run.output.rfind('{'));
}

class GplanPlansOnCpu : public ::testing::TestWithParam<std::string> {};
TEST_P(GplanPlansOnCpu, AFreePath) { expect_plans(GetParam(), "cpu"); }

class GplanPlansOnGpu : public ::testing::TestWithParam<std::string> {};
TEST_P(GplanPlansOnGpu, AFreePath) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_plans(GetParam(), "gpu");
}

std::string name_of(const ::testing::TestParamInfo<std::string>& info) {
  return testing::scene_test_name(info.param);
}
INSTANTIATE_TEST_SUITE_P(Scenes, GplanPlansOnCpu,
                         ::testing::ValuesIn(testing::shipped_scene_files()), name_of);
INSTANTIATE_TEST_SUITE_P(Scenes, GplanPlansOnGpu,
                         ::testing::ValuesIn(testing::shipped_scene_files()), name_of);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GplanPlansOnCpu);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GplanPlansOnGpu);

// The issue 21 case: a wall 2 cm thick with a window, at a coarse edge resolution (0.3,
// within the accepted range), which sampled edges and a re-check at a tenth of it jump
// over. The path gplan returns is certified: free under FCL 100 times finer than the
// planner's resolution, for every seed, with sampled or certified edges.
void expect_certified_paths_through_the_window(const std::string& backend) {
  ScratchFolder scratch;
  const std::string folder = testing::project_root() + "/benchmarks/config/error_time_ci/";
  std::ifstream in(folder + "thin_wall.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text += "  edge_resolution: 0.3\n";
  std::ifstream plate(folder + "plate.obj");
  scratch.write("plate.obj", std::string((std::istreambuf_iterator<char>(plate)),
                                         std::istreambuf_iterator<char>()));
  const std::string file = scratch.write("coarse.yaml", text);
  const Scene scene = load_scene(file);
  int through_the_wall_fine = 0;
  for (int seed = 1; seed <= 6; ++seed) {
    for (const std::string mode : {"", "--edges certified", "--path-check fine"}) {
      const std::string out = scratch.path() + "/path" + std::to_string(seed) + ".yaml";
      std::filesystem::remove(out);
      const CommandResult run =
          run_gplan("plan '" + file + "' --backend " + backend + " --seed " + std::to_string(seed) +
                    " " + mode + " --json --out '" + out + "'");
      ASSERT_EQ(run.exit_code, 0) << mode << "\n" << run.output;
      const std::string problem =
          path_recheck_problem(scene, read_path(out, scene.space.width()), 100, true);
      if (mode == "--path-check fine") {
        EXPECT_EQ(json_text(run.output, "path_check"), "fine");
        through_the_wall_fine += !problem.empty();
      } else {
        EXPECT_EQ(json_text(run.output, "path_check"), "certified");
        EXPECT_EQ(problem, "") << "seed " << seed << " " << mode;
      }
    }
  }
  // Not an expectation of the certified paths: a sign that the case is a hard one.
  std::cout << backend << ": " << through_the_wall_fine
            << " of 6 paths re-checked at a tenth of the resolution fail FCL 100 times finer\n";
}

TEST(GplanPlan, CertifiedPathsAtACoarseResolutionPassFclAHundredTimesFiner) {
  expect_certified_paths_through_the_window("cpu");
}

TEST(GplanPlanGpu, CertifiedPathsAtACoarseResolutionPassFclAHundredTimesFiner) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_certified_paths_through_the_window("gpu");
}

TEST(GplanPlan, EdgeOptionsAreChecked) {
  const std::string scene = "'" + scene_path("piano.yaml") + "'";
  for (const std::string& arguments : {std::string("--edges all"), std::string("--path-check none"),
                                       std::string("--edges certified --path-check fine")}) {
    const CommandResult run = run_gplan("plan " + scene + " --backend cpu " + arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(arguments.find("path-check") != std::string::npos ? "--path-check"
                                                                                : "--edges"),
              std::string::npos)
        << run.output;
  }
}

TEST(GplanPlan, NoPathWithinTheLimitExitsFourAndWritesNothing) {
  ScratchFolder scratch;
  const std::string out = scratch.path() + "/path.yaml";
  const CommandResult run =
      run_gplan("plan '" + scene_path("piano.yaml") +
                "' --backend cpu --milestones 20 --time-limit 0.001 --out '" + out + "'");
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_NE(run.output.find("no path found within"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(GplanPlan, PictureShowsObstaclesRobotAndPath) {
  ScratchFolder scratch;
  const std::string svg = scratch.path() + "/path.svg";
  const CommandResult run = run_gplan("plan '" + scene_path("pr2_base_arm.yaml") +
                                      "' --backend cpu --picture '" + svg + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string text = testing::read_file(svg);
  EXPECT_EQ(text.rfind("<svg", 0), 0u);
  EXPECT_NE(text.find("</svg>"), std::string::npos);
  std::size_t polygons = 0;
  for (std::size_t at = text.find("<polygon"); at != std::string::npos;
       at = text.find("<polygon", at + 1)) {
    ++polygons;
  }
  const Scene scene = load_scene(scene_path("pr2_base_arm.yaml"));
  // Every obstacle triangle but the floor's, and the robot's links at the waypoints.
  EXPECT_GT(polygons, scene.obstacle_triangle_count() / 2);
  EXPECT_NE(text.find("#2a2"), std::string::npos);  // the start pose
  EXPECT_NE(text.find("#d22"), std::string::npos);  // the goal pose
  EXPECT_NE(text.find("<polyline"), std::string::npos);
}

TEST(GplanPlan, UsageErrorsNameTheOption) {
  const std::string scene = "'" + scene_path("piano.yaml") + "'";
  for (const auto& [arguments, option] : std::vector<std::pair<std::string, std::string>>{
           {"--planner rrt", "--planner"},
           {"--backend nosuch", "--backend"},
           {"--time-limit -1", "--time-limit"},
           {"--time-limit soon", "--time-limit"},
           {"--milestones 0", "--milestones"},
           {"--seed x", "--seed"},
           {"--out /no/such/folder/p.yaml", "--out"},
           {"--picture /no/such/folder/p.svg", "--picture"},
           {"--load-roadmap /no/such/file", "--load-roadmap"},
           {"--backend cpu --traversal basic", "--traversal applies to the gpu backend only"},
           {"--bogus 1", "--bogus"}}) {
    const CommandResult run = run_gplan("plan " + scene + " " + arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(option), std::string::npos) << arguments << "\n" << run.output;
  }
  EXPECT_EQ(run_gplan("plan").exit_code, 2);
}

TEST(GplanPlan, RoadmapsAreSavedLoadedAndRefusedForOtherScenes) {
  ScratchFolder scratch;
  const std::string roadmap = scratch.path() + "/arm.roadmap";
  const std::string scene = "'" + scene_path("pr2_base_arm.yaml") + "'";
  const CommandResult first = run_gplan("plan " + scene +
                                        " --backend cpu --planner prm --milestones 250 "
                                        "--save-roadmap '" +
                                        roadmap + "'");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  ASSERT_TRUE(std::filesystem::exists(roadmap));
  const CommandResult again = run_gplan("plan " + scene +
                                        " --backend cpu --planner prm --milestones 250 --json "
                                        "--load-roadmap '" +
                                        roadmap + "'");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  // No new milestones sampled: the states checked are the loaded milestones, once each.
  std::smatch saved;
  ASSERT_TRUE(std::regex_search(first.output, saved, std::regex("roadmap +([0-9]+) milestones")));
  EXPECT_NE(again.output.find("\"states_checked\":" + saved[1].str() + ","), std::string::npos)
      << again.output;
  const CommandResult other = run_gplan("plan '" + scene_path("pr2_reach.yaml") +
                                        "' --backend cpu --load-roadmap '" + roadmap + "'");
  EXPECT_NE(other.exit_code, 0);
  EXPECT_NE(other.output.find(roadmap + ": roadmap belongs to another scene"), std::string::npos)
      << other.output;
}

}  // namespace
}  // namespace gplanner

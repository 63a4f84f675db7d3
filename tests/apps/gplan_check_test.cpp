// `gplan check` through the real binary: the --out file, the JSON summary, determinism,
// usage errors, bad scenes, and that --out is written whole or not at all.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::CommandResult;
using gplanner::testing::run_gplan;
using gplanner::testing::ScratchFolder;

// The box robot flies around a 2 m cube in the middle of the bounds. FCL intersects
// triangles, so the samples that collide are those where the robot crosses the cube's
// surface (one wholly inside counts as free): about a fifth of them.
const char* const kScene = R"(name: tiny
narrowest_passage: none; the cube is simply in the way
robot:
  mesh: box.obj
obstacles:
  - box: [2, 2, 2]
bounds:
  min: [-2, -1.5, -1]
  max: [2, 1.5, 1]
start:
  base: {xyz: [-1.8, 0, 0], quat_wxyz: [1, 0, 0, 0]}
goal:
  base: {xyz: [1.8, 0, 0], quat_wxyz: [1, 0, 0, 0]}
)";
const double kMin[3] = {-2, -1.5, -1};
const double kMax[3] = {2, 1.5, 1};
constexpr int kWidth = 7;  // x y z qw qx qy qz

// 1-based number of the first line of `text` containing `needle` (0 when none).
int line_of(const std::string& text, const std::string& needle) {
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.find(needle) != std::string::npos) return number;
  }
  ADD_FAILURE() << "no line holds '" << needle << "'";
  return 0;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string last_line(const std::string& text) {
  const std::vector<std::string> lines = lines_of(text);
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
    if (!it->empty()) return *it;
  }
  return "";
}

// The integer value of "key" in a flat JSON object, -1 when absent.
long long json_integer(const std::string& json, const std::string& key) {
  std::smatch match;
  if (!std::regex_search(json, match, std::regex("\"" + key + "\":(-?[0-9]+)[,}]"))) return -1;
  return std::stoll(match[1]);
}

// Names of everything in `folder`, for checking that nothing was left behind.
std::set<std::string> listing(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

class GplanCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_.write("box.obj", testing::kCubeObj);
    scene_ = folder_.write("scene.yaml", kScene);
  }

  std::string path(const std::string& name) const {
    return (fs::path(folder_.path()) / name).string();
  }

  CommandResult check(const std::string& arguments) const {
    return run_gplan("check " + testing::shell_quoted(scene_) + " " + arguments);
  }

  ScratchFolder folder_;
  std::string scene_;
};

TEST_F(GplanCheck, WritesOneLinePerConfigurationAndASummary) {
  const std::string out = path("samples.txt");
  const CommandResult run =
      check("--n 500 --seed 3 --out " + testing::shell_quoted(out) + " --json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(fs::is_regular_file(out)) << run.output;

  const std::string text = testing::read_file(out);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const std::vector<std::string> lines = lines_of(text);
  ASSERT_EQ(lines.size(), 500u);
  std::vector<float> configurations;
  std::vector<int> verdicts;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::istringstream fields(lines[i]);
    std::vector<std::string> words;
    for (std::string word; fields >> word;) words.push_back(word);
    ASSERT_EQ(words.size(), std::size_t{kWidth + 1}) << "line " << i + 1 << ": " << lines[i];
    double q[kWidth];
    for (int k = 0; k < kWidth; ++k) {
      std::size_t used = 0;
      q[k] = std::stod(words[k], &used);
      ASSERT_EQ(used, words[k].size()) << "line " << i + 1 << ": " << lines[i];
      ASSERT_TRUE(std::isfinite(q[k])) << "line " << i + 1 << ": " << lines[i];
      configurations.push_back(static_cast<float>(q[k]));
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(q[k], kMin[k]) << "line " << i + 1 << ": " << lines[i];
      EXPECT_LE(q[k], kMax[k]) << "line " << i + 1 << ": " << lines[i];
    }
    const double norm = std::sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
    EXPECT_NEAR(norm, 1.0, 1e-5) << "line " << i + 1 << ": " << lines[i];
    const std::string& verdict = words[kWidth];
    ASSERT_TRUE(verdict == "0" || verdict == "1") << "line " << i + 1 << ": " << lines[i];
    verdicts.push_back(verdict == "1");
  }

  const std::string json = last_line(run.output);
  ASSERT_EQ(json.front(), '{') << run.output;
  ASSERT_EQ(json.back(), '}') << run.output;
  int ones = 0;
  for (int v : verdicts) ones += v;
  EXPECT_EQ(json_integer(json, "collisions"), ones) << json;
  EXPECT_EQ(json_integer(json, "n"), 500) << json;
  EXPECT_EQ(json_integer(json, "seed"), 3) << json;
  EXPECT_EQ(json_integer(json, "width"), kWidth) << json;
  EXPECT_EQ(json_integer(json, "dof"), 6) << json;
  EXPECT_NE(json.find("\"backend\":\"fcl\""), std::string::npos) << json;
  // Both verdicts occur (about a fifth of the samples cross the cube's surface).
  EXPECT_GT(ones, 25);
  EXPECT_LT(ones, 250);

  // The verdicts are FCL's for the configurations as written.
  const Scene scene = load_scene(scene_);
  FclChecker checker(scene, 1);
  std::vector<std::uint8_t> expected(verdicts.size());
  checker.check(configurations.data(), verdicts.size(), expected.data());
  int disagreements = 0;
  for (std::size_t i = 0; i < verdicts.size(); ++i) disagreements += expected[i] != verdicts[i];
  EXPECT_EQ(disagreements, 0);
}

TEST_F(GplanCheck, SameSeedGivesTheSameFileAndAnotherSeedDoesNot) {
  const std::string a = path("a.txt"), b = path("b.txt"), c = path("c.txt");
  for (const auto& [out, seed] : {std::pair{a, 3}, std::pair{b, 3}, std::pair{c, 4}}) {
    const CommandResult run =
        check("--n 500 --seed " + std::to_string(seed) + " --out " + testing::shell_quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  const std::string first = testing::read_file(a);
  EXPECT_EQ(lines_of(first).size(), 500u);
  EXPECT_EQ(first, testing::read_file(b));
  EXPECT_NE(first, testing::read_file(c));
}

TEST_F(GplanCheck, BadSceneFailsNamingTheFileAndKey) {
  const std::string text = std::string(kScene) + "colour: red\n";
  const std::string bad = folder_.write("bad.yaml", text);
  const CommandResult run = run_gplan("check " + testing::shell_quoted(bad) + " --n 10");
  EXPECT_NE(run.exit_code, 0) << run.output;
  const std::string where = bad + ":" + std::to_string(line_of(text, "colour")) + ": colour: ";
  EXPECT_NE(run.output.find(where + "unknown key"), std::string::npos) << run.output;
}

TEST_F(GplanCheck, MissingSceneFailsNamingTheFile) {
  const std::string missing = path("nosuch.yaml");
  const CommandResult run = run_gplan("check " + testing::shell_quoted(missing));
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(missing), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("does not exist"), std::string::npos) << run.output;
}

TEST_F(GplanCheck, StartInCollisionFailsNamingTheScene) {
  std::string text = kScene;
  // Half in, half out of the cube's face at x = -1.
  text.replace(text.find("[-1.8, 0, 0]"), 12, "[-1.0, 0, 0]");
  const std::string bad = folder_.write("bad.yaml", text);
  const CommandResult run = run_gplan("check " + testing::shell_quoted(bad) + " --n 10");
  EXPECT_NE(run.exit_code, 0) << run.output;
  const std::string where = bad + ":" + std::to_string(line_of(text, "[-1.0, 0, 0]")) + ": start: ";
  EXPECT_NE(run.output.find(where + "start configuration is in collision"), std::string::npos)
      << run.output;
}

// --pairs names what collides: two cubes far apart, each colliding row must name the
// one on its side (x < 0: obstacles[0], x > 0: obstacles[1]), every free row "- -".
TEST_F(GplanCheck, PairsNameTheObstacleEachRowHits) {
  std::string text = kScene;
  text.replace(text.find("  - box: [2, 2, 2]\n"), 18,
               "  - box: [1, 1, 1]\n    pose: {xyz: [-1.2, 0, 0]}\n"
               "  - box: [1, 1, 1]\n    pose: {xyz: [1.2, 0, 0]}\n");
  text.replace(text.find("[-1.8, 0, 0]"), 12, "[0, 1.2, 0.8]");
  text.replace(text.find("[1.8, 0, 0]"), 11, "[0, -1.2, 0.8]");
  const std::string scene = folder_.write("pairs.yaml", text);
  const std::string rows = folder_.path() + "/rows.txt";
  const CommandResult run =
      run_gplan("check " + testing::shell_quoted(scene) + " --n 400 --backend cpu --out " +
                testing::shell_quoted(rows) + " --pairs");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(rows);
  std::string line;
  int colliding = 0, lines = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string field; fields >> field;) f.push_back(field);
    // A row inside a cube (solid) or within the band of one: "(no-contact)" after it.
    ASSERT_TRUE(f.size() == static_cast<std::size_t>(kWidth + 3) ||
                (f.size() == static_cast<std::size_t>(kWidth + 4) && f.back() == "(no-contact)"))
        << line;
    ++lines;
    const double x = std::stod(f[0]);
    if (f[kWidth] == "0") {
      EXPECT_EQ(f[kWidth + 1] + " " + f[kWidth + 2], "- -") << line;
      continue;
    }
    ++colliding;
    EXPECT_EQ(f[kWidth + 2], x < 0 ? "obstacles[0]" : "obstacles[1]") << line;
  }
  EXPECT_EQ(lines, 400);
  EXPECT_GT(colliding, 10);
}

TEST_F(GplanCheck, PairsNeedOut) {
  const CommandResult run = check("--n 10 --pairs");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--pairs adds the colliding pair"), std::string::npos) << run.output;
}

TEST_F(GplanCheck, UnknownOptionIsAUsageError) {
  const CommandResult run = check("--n 10 --bogus 3");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--bogus"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("usage:"), std::string::npos) << run.output;
}

TEST_F(GplanCheck, BadCountIsAUsageError) {
  for (const std::string arguments : {"--n many", "--n -5", "--n 12x", "--n=", "--n"}) {
    const CommandResult run = check(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find("--n"), std::string::npos) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find("usage:"), std::string::npos) << arguments << "\n" << run.output;
  }
}

TEST_F(GplanCheck, RepeatReportsTheMedianAndTheSameVerdicts) {
  const CommandResult once = check("--n 200 --backend cpu --json");
  const CommandResult thrice = check("--n 200 --backend cpu --repeat 3 --json");
  ASSERT_EQ(once.exit_code, 0) << once.output;
  ASSERT_EQ(thrice.exit_code, 0) << thrice.output;
  EXPECT_EQ(json_integer(last_line(thrice.output), "repeat"), 3) << thrice.output;
  EXPECT_EQ(json_integer(last_line(thrice.output), "collisions"),
            json_integer(last_line(once.output), "collisions"));
  EXPECT_NE(thrice.output.find("median of 3 runs"), std::string::npos) << thrice.output;
  const CommandResult none = check("--n 10 --repeat 0");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("--repeat"), std::string::npos) << none.output;
}

TEST_F(GplanCheck, GpuSettingsWithoutTheGpuAreAUsageError) {
  for (const std::string arguments :
       {"--n 10 --backend cpu --memory-cap-mb 1", "--n 10 --traversal basic",
        "--n 10 --backend fcl --compare cpu --traversal packet"}) {
    const CommandResult run = check(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find("applies to the gpu backend only"), std::string::npos)
        << arguments << "\n"
        << run.output;
  }
  // With the gpu backend (the cpu where there is none) they are taken.
  const CommandResult gpu = check("--n 10 --backend gpu --traversal basic --memory-cap-mb 1");
  EXPECT_EQ(gpu.exit_code, 0) << gpu.output;
}

TEST_F(GplanCheck, MissingOrExtraSceneIsAUsageError) {
  for (const std::string& arguments :
       {std::string("check"), "check " + testing::shell_quoted(scene_) + " x"}) {
    const CommandResult run = run_gplan(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find("usage:"), std::string::npos) << arguments << "\n" << run.output;
  }
}

TEST_F(GplanCheck, UnknownBackendNamesTheBackends) {
  const CommandResult run = check("--n 10 --backend nosuch");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("nosuch"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("fcl"), std::string::npos) << run.output;
}

TEST_F(GplanCheck, OutIntoMissingFolderFailsAndLeavesNothing) {
  const std::set<std::string> before = listing(folder_.path());
  const std::string out = path("missing/samples.txt");
  const CommandResult run = check("--n 50 --out " + testing::shell_quoted(out));
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("missing"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("missing")));
  EXPECT_EQ(listing(folder_.path()), before);
}

TEST_F(GplanCheck, OutIntoAFolderFailsAndLeavesItAlone) {
  fs::create_directories(path("results"));
  const std::set<std::string> before = listing(folder_.path());
  const CommandResult run = check("--n 50 --out " + testing::shell_quoted(path("results")));
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::is_directory(path("results")));
  EXPECT_TRUE(fs::is_empty(path("results")));
  EXPECT_EQ(listing(folder_.path()), before);
}

TEST_F(GplanCheck, FailedRunKeepsTheExistingOutput) {
  const std::string out = folder_.write("samples.txt", "old content\nkept\n");
  const std::string bad = folder_.write("bad.yaml", std::string(kScene) + "colour: red\n");
  const std::set<std::string> before = listing(folder_.path());

  CommandResult run = run_gplan("check " + testing::shell_quoted(bad) + " --n 50 --out " +
                                testing::shell_quoted(out));
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_EQ(testing::read_file(out), "old content\nkept\n");

  run = check("--n 50 --backend nosuch --out " + testing::shell_quoted(out));
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_EQ(testing::read_file(out), "old content\nkept\n");
  EXPECT_EQ(listing(folder_.path()), before);
}

TEST_F(GplanCheck, SuccessfulRunReplacesTheOutputWhole) {
  // Longer than what the run writes, so a write in place would leave a tail behind.
  const std::string old(200000, 'x');
  const std::string out = folder_.write("samples.txt", old);
  const std::set<std::string> before = listing(folder_.path());
  const CommandResult run = check("--n 20 --seed 3 --out " + testing::shell_quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string text = testing::read_file(out);
  EXPECT_EQ(text.find('x'), std::string::npos);
  EXPECT_EQ(lines_of(text).size(), 20u);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(listing(folder_.path()), before);  // no temporary file left beside it
}

}  // namespace
}  // namespace gplanner

// Counts on gplan's command line through the real program: every integer option refuses
// overflowing, negative, signed, fractional and too-large values with exit 2 and a line
// naming the option, the value and the accepted range, before any work; --n is also
// held to memory. (Before: --n 2635249153387078803 wrapped n * width and wrote past a
// 5-float buffer, --threads 4294967297 was cast to 1, --threads 100000 tried to start
// 100,000 threads.)

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gplanner/common/physical_memory.h"
#include "gplanner/planner/planning/roadmap.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::CommandResult;
using testing::run_gplan;

std::string piano() { return "'" + testing::project_root() + "/scenes/piano.yaml'"; }

void expect_refused(const std::string& command, const std::string& option, const std::string& value,
                    const std::string& range) {
  const CommandResult run = run_gplan(command + " " + piano() + " " + option + " " + value);
  EXPECT_EQ(run.exit_code, 2) << option << " " << value << "\n" << run.output;
  EXPECT_NE(run.output.find(option + " expects a whole number from " + range), std::string::npos)
      << option << " " << value << "\n"
      << run.output;
  EXPECT_EQ(run.output.find("Segmentation"), std::string::npos) << run.output;
}

// Values no count accepts: beyond 64 bits, negative, signed, fractional, not a number,
// empty, spaced.
const std::vector<std::string> kNeverCounts = {"18446744073709551616",
                                               "99999999999999999999999",
                                               "-1",
                                               "-0",
                                               "+5",
                                               "1.9",
                                               "1e3",
                                               "x",
                                               "''",
                                               "' 7'",
                                               "0x10"};

TEST(GplanCountRanges, CheckRefusesEveryBadCountNamingOptionAndRange) {
  const std::vector<std::pair<std::string, std::string>> options = {
      {"--n", "1 to 1000000000"},
      {"--seed", "0 to 18446744073709551615"},
      {"--repeat", "1 to 1000"},
      {"--threads", "0 to 1024"},
      {"--memory-cap-mb", "0 to 16777216"},
      {"--small-batch", "0 to 1000000000"}};
  for (const auto& [option, range] : options) {
    for (const std::string& value : kNeverCounts) {
      if (option == "--seed" && value == "-0") continue;
      expect_refused("check", option, value, range);
    }
  }
  // Within 64 bits but beyond the option's range: the values of the issue among them.
  expect_refused("check", "--n", "2635249153387078803", "1 to 1000000000");
  expect_refused("check", "--n", "0", "1 to 1000000000");
  expect_refused("check", "--threads", "4294967297", "0 to 1024");
  expect_refused("check", "--threads", "100000", "0 to 1024");
  expect_refused("check", "--repeat", "0", "1 to 1000");
  expect_refused("check", "--repeat", "1001", "1 to 1000");
  expect_refused("check", "--memory-cap-mb", "17592186044416", "0 to 16777216");
}

TEST(GplanCountRanges, PlanRefusesEveryBadCountNamingOptionAndRange) {
  for (const auto& [option, range] :
       std::vector<std::pair<std::string, std::string>>{{"--seed", "0 to 18446744073709551615"},
                                                        {"--threads", "0 to 1024"},
                                                        {"--milestones", "1 to 100000000"}}) {
    for (const std::string& value : kNeverCounts) {
      if (option == "--seed" && value == "-0") continue;
      expect_refused("plan", option, value, range);
    }
  }
  expect_refused("plan", "--threads", "4294967297", "0 to 1024");
  expect_refused("plan", "--milestones", "0", "1 to 100000000");
  expect_refused("plan", "--milestones", "100000001", "1 to 100000000");
}

TEST(GplanCountRanges, FullSeedRangeIsAccepted) {
  const CommandResult run =
      run_gplan("check " + piano() + " --backend cpu --n 5 --seed 18446744073709551615 --json");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("\"seed\":18446744073709551615"), std::string::npos) << run.output;
}

TEST(GplanCountRanges, RowsBeyondMemoryAreRefusedWithTheEstimate) {
  // 1e9 rows of the piano's 7 floats and their verdicts: 30 GB.
  if (fits_in_memory(1e9 * (7 * 4 + 2))) GTEST_SKIP() << "30 GB is within half this memory";
  const CommandResult run = run_gplan("check " + piano() + " --backend cpu --n 1000000000");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--n 1000000000: 7-float rows need about"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("give a smaller --n"), std::string::npos) << run.output;
}

TEST(GplanCountRanges, RoadmapBeyondMemoryIsRefusedWithTheEstimate) {
  // 1e8 milestones of the piano (7 floats, 15 neighbours): about 57 GB of roadmap.
  if (fits_in_memory(roadmap_bytes(100000000, 7, 15)))
    GTEST_SKIP() << "the roadmap fits within half this memory";
  const CommandResult run =
      run_gplan("plan " + piano() + " --backend cpu --milestones 100000000 --time-limit 1");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--milestones: the roadmap of 100000000 milestones needs about"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("give fewer milestones"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace gplanner

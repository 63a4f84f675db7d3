// How gplan-bench shares the machine: the notice that single-threaded planners run side
// by side (--jobs above 1) are slower than alone.

#include "harness/bench_runner.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace gplan {
namespace {

// Groups that run alone (ours) and `together` single-threaded ones (OMPL's).
std::vector<BenchGroup> groups_with(int alone, int together) {
  std::vector<BenchGroup> groups;
  for (int i = 0; i < alone + together; ++i) {
    BenchGroup g;
    g.scene_name = "scene" + std::to_string(i);
    g.alone = i < alone;
    groups.push_back(g);
  }
  return groups;
}

TEST(SideBySideNotice, SaysWhenSingleThreadedPlannersRanTogether) {
  const std::string notice = side_by_side_notice(groups_with(2, 14), 12);
  EXPECT_NE(notice.find("--jobs 12"), std::string::npos) << notice;
  EXPECT_NE(notice.find("up to 12 at a time"), std::string::npos) << notice;
  EXPECT_NE(notice.find("--jobs 1"), std::string::npos) << notice;
  // Fewer groups than jobs: only those ran together.
  EXPECT_NE(side_by_side_notice(groups_with(0, 3), 12).find("up to 3 at a time"),
            std::string::npos);
}

TEST(SideBySideNotice, SilentWhereEachRanAlone) {
  EXPECT_EQ(side_by_side_notice(groups_with(2, 14), 1), "");  // one at a time
  EXPECT_EQ(side_by_side_notice(groups_with(5, 1), 12), "");  // one single-threaded group
  EXPECT_EQ(side_by_side_notice(groups_with(5, 0), 12), "");  // ours only: each runs alone
}

}  // namespace
}  // namespace gplan

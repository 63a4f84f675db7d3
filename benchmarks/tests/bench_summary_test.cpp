// The summary of a bench run's records and the verdict against a baseline, on records
// whose figures are known by construction.

#include "harness/bench_summary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "harness/bench_baseline.h"
#include "gplanner/planner/scene/input_error.h"
#include "test_support.h"

namespace gplan {
namespace {

BenchRecord run(const std::string& planner, const std::string& checker, double time, bool solved,
                double length = 10) {
  BenchRecord r;
  r.experiment = "e";
  r.scene = "s";
  r.planner = planner;
  r.checker = checker;
  r.time_s = time;
  r.solved = solved;
  r.status = solved ? "exact" : "timeout";
  if (solved) {
    r.simplified_length = length;
    r.path_check = "pass";
  }
  return r;
}

std::vector<BenchRecord> sample_records() {
  return {run("ours-lazyprm", "gpu", 0.1, true, 8), run("ours-lazyprm", "gpu", 0.3, true, 12),
          run("ours-lazyprm", "gpu", 0.2, true, 10),
          run("ompl-rrtconnect", "fcl", 2, true), run("ompl-rrtconnect", "fcl", 10, false),
          run("ompl-rrtconnect", "fcl", 4, true),
          run("ompl-prm", "fcl", 10, false), run("ompl-prm", "fcl", 10, false),
          run("ompl-prm", "fcl", 1, true),
          run("ompl-prm", "gpu", 0.5, true), run("ompl-prm", "gpu", 0.5, true)};
}

TEST(BenchSummary, MediansSuccessAndTheFclReference) {
  const std::vector<GroupSummary> groups = summarize(sample_records());
  ASSERT_EQ(groups.size(), 4u);
  const GroupSummary& ours = groups[0];
  EXPECT_EQ(ours.key(), "s ours-lazyprm@gpu");
  EXPECT_EQ(ours.runs, 3);
  EXPECT_EQ(ours.solved, 3);
  EXPECT_DOUBLE_EQ(ours.success_rate, 1);
  EXPECT_DOUBLE_EQ(ours.median_time_s, 0.2);
  EXPECT_DOUBLE_EQ(ours.min_time_s, 0.1);
  EXPECT_DOUBLE_EQ(ours.max_time_s, 0.3);
  EXPECT_DOUBLE_EQ(ours.median_length, 10);
  EXPECT_FALSE(ours.median_is_lower_bound);
  // Ours against the fastest FCL group (RRTConnect, median 4 s): 20x.
  EXPECT_EQ(ours.reference, "ompl-rrtconnect@fcl");
  EXPECT_NEAR(ours.speedup_over_fcl, 20, 1e-9);
  // OMPL's PRM through the plugin against OMPL's PRM with FCL (median 10 s, a lower
  // bound: two of three runs found no path).
  const GroupSummary& prm_fcl = groups[2];
  EXPECT_TRUE(prm_fcl.median_is_lower_bound);
  EXPECT_NEAR(prm_fcl.success_rate, 1.0 / 3, 1e-12);
  EXPECT_TRUE(std::isnan(prm_fcl.speedup_over_fcl));  // no reference but itself
  const GroupSummary& prm_gpu = groups[3];
  EXPECT_EQ(prm_gpu.reference, "ompl-prm@fcl");
  EXPECT_NEAR(prm_gpu.speedup_over_fcl, 20, 1e-9);
  EXPECT_TRUE(prm_gpu.reference_is_lower_bound);

  std::ostringstream table;
  print_summary(table, groups);
  EXPECT_NE(table.str().find(">20x (ompl-prm@fcl)"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find(">10.0 s"), std::string::npos) << table.str();
}

TEST(BenchSummary, PathsThatFailTheRecheckAreCounted) {
  std::vector<BenchRecord> records = sample_records();
  records[1].path_check = "fail";
  const std::vector<GroupSummary> groups = summarize(records);
  EXPECT_EQ(groups[0].path_failures, 1);
  std::ostringstream table;
  print_summary(table, groups);
  EXPECT_NE(table.str().find("1 of 3 FAILED"), std::string::npos) << table.str();
}

TEST(BenchSummary, TheShareOfThePlanTimeInChecksIsTheMedianOverRuns) {
  std::vector<BenchRecord> records = sample_records();
  records[3].check_time_s = 1.8;  // ompl-rrtconnect@fcl: 2 s, 90%
  records[4].check_time_s = 5;    // 10 s, 50%
  records[5].check_time_s = 3;    // 4 s, 75%
  const std::vector<GroupSummary> groups = summarize(records);
  EXPECT_NEAR(groups[1].median_check_share, 0.75, 1e-12);
  EXPECT_TRUE(std::isnan(groups[0].median_check_share));  // not measured
  std::ostringstream table;
  print_summary(table, groups);
  EXPECT_NE(table.str().find("in checks"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find(" 75% "), std::string::npos) << table.str();
}

TEST(BenchRecord, CsvsWrittenBeforeTheCheckTimeColumnAreStillRead) {
  const gplanner::testing::ScratchFolder folder;
  const std::string file = folder.path() + "/old.csv";
  {
    std::ofstream out(file);
    out << "experiment,scene,planner,checker,run,seed,status,solved,time_s,simplify_time_s,"
           "length,simplified_length,checks,graph_states,memory_mb,path_check,work,"
           "collisions,note\n"
           "e,s,ompl-prm,fcl,0,1,exact,1,2.5,,10,,300,40,20,pass,,,\n";
  }
  const std::vector<BenchRecord> records = read_bench_csv(file);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].checks, 300);
  EXPECT_EQ(records[0].graph_states, 40);
  EXPECT_TRUE(std::isnan(records[0].check_time_s));
  // And this version's, the check time written and read back.
  BenchRecord record = records[0];
  record.check_time_s = 1.25;
  const std::string now = folder.path() + "/now.csv";
  {
    std::ofstream out(now);
    write_bench_csv_header(out);
    write_bench_csv_line(out, record);
  }
  const std::vector<BenchRecord> again = read_bench_csv(now);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_DOUBLE_EQ(again[0].check_time_s, 1.25);
  EXPECT_EQ(again[0].graph_states, 40);
  // A record of the old width under this version's header is refused, naming the line.
  {
    std::ofstream out(now, std::ios::app);
    out << "e,s,ompl-prm,fcl,0,1,exact,1,2.5,,10,,300,40,20,pass,,,\n";
  }
  try {
    read_bench_csv(now);
    ADD_FAILURE() << "a short record was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("now.csv:3: 19 fields, not 20"), std::string::npos)
        << e.what();
  }
}

TEST(BenchBaseline, WithinToleranceAndEachPlantedRegression) {
  const std::vector<GroupSummary> run = summarize(sample_records());
  const BenchTolerances tolerances;  // time 1.5x (and 0.05 s), success 0.2, length 1.25x
  EXPECT_FALSE(compare_with_baseline(run, run, tolerances).regressed());

  std::vector<GroupSummary> faster = run;
  faster[0].median_time_s = 0.1;  // ours took 0.2 s: 2x the baseline, 0.1 s more
  BaselineVerdict verdict = compare_with_baseline(run, faster, tolerances);
  ASSERT_EQ(verdict.regressions.size(), 1u);
  EXPECT_NE(verdict.regressions[0].find("s ours-lazyprm@gpu: median time 0.2 s"), std::string::npos)
      << verdict.regressions[0];

  BenchTolerances loose = tolerances;
  loose.time_floor_s = 0.5;  // the same slowdown, but by less than the floor
  EXPECT_FALSE(compare_with_baseline(run, faster, loose).regressed());

  std::vector<GroupSummary> more_successful = run;
  more_successful[2].success_rate = 1;  // OMPL's PRM solved 1 of 3
  verdict = compare_with_baseline(run, more_successful, tolerances);
  ASSERT_EQ(verdict.regressions.size(), 1u);
  EXPECT_NE(verdict.regressions[0].find("success rate"), std::string::npos);

  std::vector<GroupSummary> shorter = run;
  shorter[0].median_length = 7;  // 10 now: 1.43x
  verdict = compare_with_baseline(run, shorter, tolerances);
  ASSERT_EQ(verdict.regressions.size(), 1u);
  EXPECT_NE(verdict.regressions[0].find("path length"), std::string::npos);

  std::vector<GroupSummary> more_groups = run;
  more_groups.push_back(run[0]);
  more_groups.back().checker = "cpu";
  verdict = compare_with_baseline(run, more_groups, tolerances);
  ASSERT_EQ(verdict.regressions.size(), 1u);
  EXPECT_NE(verdict.regressions[0].find("not in this run"), std::string::npos);

  const std::vector<GroupSummary> fewer(run.begin(), run.begin() + 1);
  verdict = compare_with_baseline(run, fewer, tolerances);
  EXPECT_FALSE(verdict.regressed());
  EXPECT_EQ(verdict.notes.size(), 3u);
}

TEST(BenchBaseline, SavedAndLoadedAlike) {
  const gplanner::testing::ScratchFolder folder;
  const std::string file = folder.path() + "/baseline.yaml";
  const std::vector<GroupSummary> run = summarize(sample_records());
  save_baseline(file, "config.yaml", run);
  const std::vector<GroupSummary> loaded = load_baseline(file);
  ASSERT_EQ(loaded.size(), run.size());
  for (std::size_t i = 0; i < run.size(); ++i) {
    EXPECT_EQ(loaded[i].key(), run[i].key());
    EXPECT_EQ(loaded[i].runs, run[i].runs);
    EXPECT_NEAR(loaded[i].success_rate, run[i].success_rate, 1e-3);
    EXPECT_NEAR(loaded[i].median_time_s, run[i].median_time_s, 1e-3 * run[i].median_time_s);
  }
  EXPECT_FALSE(compare_with_baseline(run, loaded, BenchTolerances{}).regressed());
}

TEST(BenchBaseline, ABrokenBaselineIsRefusedWithItsLineAndKey) {
  const gplanner::testing::ScratchFolder folder;
  const std::string file = folder.write(
      "baseline.yaml",
      "gplan_bench_baseline: 1\ngroups:\n  - {scene: s, planner: p, checker: fcl, runs: 3,\n"
      "     success_rate: 1.5, median_time_s: 1}\n");
  try {
    load_baseline(file);
    FAIL() << "accepted";
  } catch (const gplanner::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":4: groups[0].success_rate: must be from 0 to 1"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gplan

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

TEST(BenchRecord, CsvsOfEarlierVersionsAreStillRead) {
  const gplanner::testing::ScratchFolder folder;
  const std::string before_issue22 = folder.write(
      "old.csv",
      "experiment,scene,planner,checker,run,seed,status,solved,time_s,simplify_time_s,"
      "length,simplified_length,checks,graph_states,memory_mb,path_check,work,collisions,note\n"
      "e,s,ompl-prm,fcl,0,1,exact,1,2.5,,10,,300,40,20,pass,,,\n");
  const std::vector<BenchRecord> records = read_bench_csv(before_issue22);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].checks, 300);
  EXPECT_EQ(records[0].graph_states, 40);
  EXPECT_TRUE(std::isnan(records[0].check_time_s));
  EXPECT_TRUE(std::isnan(records[0].sampling_s));
  EXPECT_EQ(records[0].rounds, -1);
  // Issue 22 to 32: check_time_s, no stage columns.
  const std::string before_issue33 = folder.write(
      "issue32.csv",
      "experiment,scene,planner,checker,run,seed,status,solved,time_s,simplify_time_s,"
      "length,simplified_length,checks,check_time_s,graph_states,memory_mb,path_check,work,"
      "collisions,note\n"
      "e,s,ours-lazyprm,gpu,0,1,exact,1,0.05,0.01,10,9,300,,40,20,pass,,,\n");
  const std::vector<BenchRecord> issue32 = read_bench_csv(before_issue33);
  ASSERT_EQ(issue32.size(), 1u);
  EXPECT_EQ(issue32[0].graph_states, 40);
  EXPECT_DOUBLE_EQ(issue32[0].simplify_time_s, 0.01);
  EXPECT_TRUE(std::isnan(issue32[0].knn_s));
  // Issue 33's first figures: the stages, no gpu_calls.
  const std::string issue33_first = folder.write(
      "issue33.csv",
      "experiment,scene,planner,checker,run,seed,status,solved,time_s,simplify_time_s,"
      "length,simplified_length,checks,check_time_s,graph_states,memory_mb,path_check,work,"
      "collisions,sampling_s,state_checks_s,knn_s,search_s,edge_checks_s,rounds,note\n"
      "e,s,ours-lazyprm,gpu,0,1,exact,1,0.05,0.01,10,9,300,,40,20,pass,,,0.5,0.25,1,2,3,4,\n");
  const std::vector<BenchRecord> issue33 = read_bench_csv(issue33_first);
  ASSERT_EQ(issue33.size(), 1u);
  EXPECT_DOUBLE_EQ(issue33[0].knn_s, 1);
  EXPECT_EQ(issue33[0].rounds, 4);
  EXPECT_EQ(issue33[0].gpu_calls, -1);
  // Issue 33 to 35: gpu_calls, no device.
  const std::string before_issue36 = folder.write(
      "issue35.csv",
      "experiment,scene,planner,checker,run,seed,status,solved,time_s,simplify_time_s,"
      "length,simplified_length,checks,check_time_s,graph_states,memory_mb,path_check,work,"
      "collisions,sampling_s,state_checks_s,knn_s,search_s,edge_checks_s,rounds,gpu_calls,"
      "note\n"
      "e,s,ours-auto,gpu,0,1,exact,1,0.05,0.01,10,9,300,,40,20,pass,,,0.5,0.25,1,2,3,4,11,\n");
  const std::vector<BenchRecord> issue35 = read_bench_csv(before_issue36);
  ASSERT_EQ(issue35.size(), 1u);
  EXPECT_EQ(issue35[0].gpu_calls, 11);
  EXPECT_EQ(issue35[0].device, -1);
  // And this version's: the check time and the stages written and read back.
  BenchRecord record = records[0];
  record.check_time_s = 1.25;
  record.sampling_s = 0.125;
  record.state_checks_s = 0.25;
  record.knn_s = 0.5;
  record.search_s = 0.0625;
  record.edge_checks_s = 0.375;
  record.rounds = 3;
  record.gpu_calls = 17;
  record.device = 3;
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
  EXPECT_DOUBLE_EQ(again[0].sampling_s, 0.125);
  EXPECT_DOUBLE_EQ(again[0].state_checks_s, 0.25);
  EXPECT_DOUBLE_EQ(again[0].knn_s, 0.5);
  EXPECT_DOUBLE_EQ(again[0].search_s, 0.0625);
  EXPECT_DOUBLE_EQ(again[0].edge_checks_s, 0.375);
  EXPECT_EQ(again[0].rounds, 3);
  EXPECT_EQ(again[0].gpu_calls, 17);
  EXPECT_EQ(again[0].device, 3);
  EXPECT_EQ(again[0].note, "");
  // A record of the old width under this version's header is refused, naming the line.
  {
    std::ofstream out(now, std::ios::app);
    out << "e,s,ompl-prm,fcl,0,1,exact,1,2.5,,10,,300,40,20,pass,,,\n";
  }
  try {
    read_bench_csv(now);
    ADD_FAILURE() << "a short record was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("now.csv:3: 19 fields, not 28"), std::string::npos)
        << e.what();
  }
}

// Where our planners' time goes: per group, over its solved runs, the median of each
// stage and of what lies beyond them; OMPL's groups (no stage times) left out.
TEST(BenchSummary, StageTableOfOurPlannersSolvedRuns) {
  std::vector<BenchRecord> records;
  for (int i = 0; i < 3; ++i) {
    BenchRecord r;
    r.scene = "cage";
    r.planner = "ours-lazyprm";
    r.checker = "gpu";
    r.run = i;
    r.solved = i < 2;
    r.time_s = i < 2 ? 1.0 + i : 10;  // 1 s and 2 s solved; a 10 s run without a path
    r.sampling_s = 0.01;
    r.state_checks_s = 0.1;
    r.knn_s = 0.2;
    r.search_s = 0.4 * (1 + i);  // 0.4 s and 0.8 s
    r.edge_checks_s = 0.05;
    r.simplify_time_s = 0.02;
    r.rounds = 4 + i;
    records.push_back(r);
  }
  BenchRecord ompl;
  ompl.scene = "cage";
  ompl.planner = "ompl-rrtconnect";
  ompl.checker = "fcl";
  ompl.solved = true;
  ompl.time_s = 0.5;
  records.push_back(ompl);
  std::ostringstream table;
  print_stage_summary(table, records);
  const std::string text = table.str();
  EXPECT_NE(text.find("stages (our planners' solved runs"), std::string::npos) << text;
  EXPECT_NE(text.find("ours-lazyprm@gpu"), std::string::npos) << text;
  EXPECT_EQ(text.find("ompl-rrtconnect"), std::string::npos) << text;
  EXPECT_NE(text.find("2/3"), std::string::npos) << text;       // solved / runs
  EXPECT_NE(text.find("1.50 s"), std::string::npos) << text;    // plan time
  EXPECT_NE(text.find("600.0 ms"), std::string::npos) << text;  // search
  // Other: 1 - 0.78 = 0.22 s and 2 - 1.18 = 0.82 s, median 0.52 s.
  EXPECT_NE(text.find("520.0 ms"), std::string::npos) << text;
  EXPECT_NE(text.find("4.5"), std::string::npos) << text;  // rounds
  std::ostringstream none;
  print_stage_summary(none, {ompl});
  EXPECT_EQ(none.str(), "");
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

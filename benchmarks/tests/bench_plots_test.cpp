// gplan bench's plots (benchmarks/harness/bench_plots, the embedded plot_bench.py): every figure
// drawn as PNG and SVG from a synthetic run's CSV, the same bytes when drawn twice, into
// folders whose names hold spaces and quotes; a clear notice, never a crash, when there is
// no python3 with matplotlib or the CSV is not gplan's. The drawing tests need matplotlib
// (scripts/setup.sh installs python3-matplotlib) and fail without it.

#include "harness/bench_plots.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "harness/bench_record.h"
#include "test_support.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::read_file;
using gplanner::testing::ScratchFolder;

// Sets (or, with nullptr, removes) an environment variable for one test.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) {
      had_ = true;
      old_ = old;
    }
    if (value != nullptr) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnvironment() {
    if (had_) {
      setenv(name_.c_str(), old_.c_str(), 1);
    } else {
      unsetenv(name_.c_str());
    }
  }

 private:
  std::string name_;
  std::string old_;
  bool had_ = false;
};

BenchRecord planning_run(const std::string& experiment, const std::string& scene,
                         const std::string& planner, const std::string& checker, int run,
                         bool solved, double time_s) {
  BenchRecord r;
  r.experiment = experiment;
  r.scene = scene;
  r.planner = planner;
  r.checker = checker;
  r.run = run;
  r.seed = 1000 + static_cast<std::uint64_t>(run);
  r.status = solved ? "exact" : "timeout";
  r.solved = solved;
  r.time_s = time_s;
  if (solved) {
    r.length = 3.5 + run;
    r.path_check = "pass";
  }
  return r;
}

// Two scenes, ours and OMPL's planners on several checkers, solved and unsolved runs (at
// the time limit, 5 s), a run that ended in an error (no time); and a collision-queries
// table over both scenes.
std::vector<BenchRecord> synthetic_run(const std::string& experiment) {
  std::vector<BenchRecord> records;
  const std::vector<std::pair<std::string, std::string>> groups = {
      {"ours-lazyprm", "gpu"},    {"ours-lazyprm", "cpu"},    {"ours-prm", "gpu"},
      {"ompl-rrtconnect", "fcl"}, {"ompl-rrtconnect", "gpu"}, {"ompl-prm", "fcl"}};
  int group_index = 0;
  for (const std::string scene : {"piano", "helicopter"}) {
    for (const auto& [planner, checker] : groups) {
      ++group_index;
      for (int run = 0; run < 5; ++run) {
        const bool solved = (run + group_index) % 4 != 0;
        const double time_s = solved ? 0.02 * (group_index + 1) * (run + 1) : 5.0;
        records.push_back(planning_run(experiment, scene, planner, checker, run, solved, time_s));
      }
    }
    BenchRecord error = planning_run(experiment, scene, "ompl-prm", "fcl", 5, false, kNotMeasured);
    error.status = "error";
    error.note = "std::bad_alloc";
    records.push_back(error);
    for (const std::string checker : {"gpu-basic", "gpu-packet", "cpu", "fcl"}) {
      for (int batch = 0; batch < 3; ++batch) {
        BenchRecord r;
        r.experiment = experiment;
        r.scene = scene;
        r.planner = "collision-queries";
        r.checker = checker;
        r.run = batch;
        r.status = "measured";
        r.time_s = (checker == "fcl" ? 15.9 : checker == "cpu" ? 2.1 : 0.39) * (1 + batch * 0.1);
        r.work = 50000;
        r.collisions = 12345;
        records.push_back(r);
      }
    }
  }
  return records;
}

std::string write_csv(const ScratchFolder& scratch, const std::string& name,
                      const std::vector<BenchRecord>& records) {
  const std::string path = scratch.path() + "/" + name;
  std::ofstream out(path);
  write_bench_csv_header(out);
  for (const BenchRecord& record : records) write_bench_csv_line(out, record);
  return path;
}

std::set<std::string> files_in(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.insert(entry.path().filename().string());
  return names;
}

std::set<std::string> png_and_svg(const std::vector<std::string>& stems) {
  std::set<std::string> names;
  for (const std::string& stem : stems) {
    names.insert(stem + ".png");
    names.insert(stem + ".svg");
  }
  return names;
}

void expect_png(const std::string& path) {
  const std::string content = read_file(path);
  EXPECT_EQ(content.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << path;
  EXPECT_GT(content.size(), 1000u) << path;
}

void expect_svg(const std::string& path) {
  const std::string content = read_file(path);
  EXPECT_EQ(content.rfind("<?xml", 0), 0u) << path;
  EXPECT_NE(content.find("<svg"), std::string::npos) << path;
  EXPECT_NE(content.find("</svg>"), std::string::npos) << path;
  // Deterministic: no date in the metadata.
  EXPECT_EQ(content.find("<dc:date>"), std::string::npos) << path;
}

TEST(BenchPlots, DrawsEveryFigureAsPngAndSvgTheSameWhenDrawnTwice) {
  ScopedEnvironment no_choice("GPLANNER_PYTHON", nullptr);
  ScratchFolder scratch;
  const std::string csv = write_csv(scratch, "results.csv", synthetic_run("small"));
  // Folder names a shell would split or unquote: the script runs without one.
  const std::string first = scratch.path() + "/plots 'one'";
  const std::string second = scratch.path() + "/plots \"two\" $HOME";

  std::string notice = "left from before";
  ASSERT_TRUE(draw_bench_plots(csv, first, &notice))
      << notice << " (scripts/setup.sh installs python3-matplotlib)";
  EXPECT_EQ(notice, "");
  ASSERT_TRUE(draw_bench_plots(csv, second, &notice)) << notice;

  const std::set<std::string> expected =
      png_and_svg({"piano", "helicopter", "plan_times", "collision-queries"});
  EXPECT_EQ(files_in(first), expected);
  EXPECT_EQ(files_in(second), expected);
  for (const std::string& name : expected) {
    const std::string path = first + "/" + name;
    if (name.size() > 4 && name.substr(name.size() - 4) == ".png") {
      expect_png(path);
    } else {
      expect_svg(path);
    }
    EXPECT_TRUE(read_file(path) == read_file(second + "/" + name)) << name << " differs";
  }
  // What the figures say (matplotlib keeps each text as a comment in the SVG): piano's
  // solved/runs (ours-prm@gpu lost two runs; ompl-prm@fcl has one more, with no time),
  // the fastest FCL group (median 0.4 s against 0.56 s) as the baseline; the query
  // table's medians and the batch size.
  const std::string piano = read_file(first + "/piano.svg");
  EXPECT_NE(piano.find("<!-- small: plan time per planner@checker, seconds (log scale) -->"),
            std::string::npos);
  EXPECT_NE(piano.find("<!-- piano -->"), std::string::npos);
  EXPECT_NE(piano.find("<!-- 3/5 -->"), std::string::npos);
  EXPECT_NE(piano.find("<!-- 4/6 (1 untimed) -->"), std::string::npos);
  const std::size_t baseline_group = piano.find("<!-- ompl-rrtconnect@fcl -->");
  ASSERT_NE(baseline_group, std::string::npos);
  EXPECT_EQ(piano.find("<!--", baseline_group + 4), piano.find("<!-- (baseline) -->"));
  const std::string queries = read_file(first + "/collision-queries.svg");
  EXPECT_NE(queries.find("<!-- 429 ms -->"), std::string::npos);
  EXPECT_NE(queries.find("<!-- 17.5 s -->"), std::string::npos);
  EXPECT_NE(queries.find("50000 configurations"), std::string::npos);

  // Drawn again over the same folder: replaced whole, nothing left beside them.
  ASSERT_TRUE(draw_bench_plots(csv, first, &notice)) << notice;
  EXPECT_EQ(files_in(first), expected);
  EXPECT_TRUE(read_file(first + "/plan_times.png") == read_file(second + "/plan_times.png"));
}

TEST(BenchPlots, SeveralExperimentsInOneCsvGetAFolderEach) {
  ScopedEnvironment no_choice("GPLANNER_PYTHON", nullptr);
  ScratchFolder scratch;
  std::vector<BenchRecord> records = synthetic_run("first");
  for (BenchRecord r : synthetic_run("second")) {
    if (r.planner != "collision-queries") continue;  // only a query table in the second
    r.planner = "local-planning";
    records.push_back(r);
  }
  const std::string csv = write_csv(scratch, "results.csv", records);
  const std::string out = scratch.path() + "/plots";
  std::string notice;
  ASSERT_TRUE(draw_bench_plots(csv, out, &notice)) << notice;
  EXPECT_EQ(files_in(out), (std::set<std::string>{"first", "second"}));
  EXPECT_EQ(files_in(out + "/first"),
            png_and_svg({"piano", "helicopter", "plan_times", "collision-queries"}));
  EXPECT_EQ(files_in(out + "/second"), png_and_svg({"local-planning"}));
  expect_png(out + "/second/local-planning.png");
  expect_svg(out + "/second/local-planning.svg");
}

TEST(BenchPlots, NoPythonWithMatplotlibGivesANoticeSayingWhatToInstall) {
  ScratchFolder scratch;
  const std::string csv = write_csv(scratch, "results.csv", synthetic_run("small"));
  // A python3 that runs but has no matplotlib: a module of that name that fails to import.
  fs::create_directories(scratch.path() + "/shadow");
  scratch.write("shadow/matplotlib.py", "raise ImportError('no matplotlib here')\n");
  const std::string without =
      scratch.write("python without matplotlib",
                    "#!/bin/sh\nPYTHONPATH='" + scratch.path() + "/shadow' exec python3 \"$@\"\n");
  fs::permissions(without, fs::perms::owner_all);

  for (const std::string& python : {std::string("/bin/false"), std::string("/bin/true"),
                                    scratch.path() + "/no such python3", without}) {
    ScopedEnvironment chosen("GPLANNER_PYTHON", python.c_str());
    const std::string out = scratch.path() + "/plots";
    std::string notice;
    EXPECT_FALSE(draw_bench_plots(csv, out, &notice)) << python;
    EXPECT_NE(notice.find("apt-get install python3-matplotlib"), std::string::npos) << notice;
    EXPECT_NE(notice.find("GPLANNER_PYTHON=" + python), std::string::npos) << notice;
    EXPECT_EQ(notice.find('\n'), std::string::npos) << "one line: " << notice;
    EXPECT_FALSE(fs::exists(out)) << python;
  }
}

TEST(BenchPlots, ACsvThatIsNotGplansGivesANoticeAndNoFigure) {
  ScopedEnvironment no_choice("GPLANNER_PYTHON", nullptr);
  ScratchFolder scratch;
  const std::string bad_header = scratch.write("bad header.csv", "experiment,scene\nx,y\n");
  const std::string out = scratch.path() + "/plots";
  std::string notice;
  EXPECT_FALSE(draw_bench_plots(bad_header, out, &notice));
  EXPECT_NE(notice.find("exited with code 2"), std::string::npos) << notice;
  EXPECT_FALSE(fs::exists(out));

  // A record whose time is no number: refused before anything is drawn.
  const std::string header = read_file(write_csv(scratch, "header.csv", {}));
  const std::string bad_time = scratch.write(
      "bad time.csv", header + "small,piano,ours-prm,gpu,0,1,exact,1,fast,,,,,,,,,,\n");
  EXPECT_FALSE(draw_bench_plots(bad_time, out, &notice));
  EXPECT_NE(notice.find("exited with code 2"), std::string::npos) << notice;
  EXPECT_FALSE(fs::exists(out));

  EXPECT_FALSE(draw_bench_plots(scratch.path() + "/missing.csv", out, &notice));
  EXPECT_NE(notice.find("exited with code 2"), std::string::npos) << notice;
}

}  // namespace
}  // namespace gplan

#include "harness/bench_command.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "command_line.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/output/output_paths.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/scene.h"
#include "harness/bench_baseline.h"
#include "harness/bench_config.h"
#include "harness/bench_files.h"
#include "harness/bench_plots.h"
#include "harness/bench_record.h"
#include "harness/bench_runner.h"
#include "harness/bench_summary.h"
#include "harness/broad_phase_study.h"
#include "harness/error_time_study.h"
#include "harness/ompl_log.h"
#include "interruption.h"

namespace gplan {

const char* const kBenchUsage =
    "usage: gplan-bench CONFIG [-o DIR] [--jobs N] [--gpus N] [--threads N]\n"
    "                   [--baseline FILE] [--save-baseline FILE] [--shard I/N] [--report DIR]\n"
    "                   [--no-plots]\n"
    "      regression runs and the seed's tables as a configuration (benchmarks/config/*.yaml)\n"
    "      says: every run in a worker process with its own seed, progress on stderr;\n"
    "      writes DIR (default gplan-bench-NAME-DATE-TIME; a new or empty folder):\n"
    "      results.csv, summary.txt (also printed), ompl/SCENE.log (OMPL's benchmark log,\n"
    "      for ompl_benchmark_statistics), plots/ (PNG and SVG, with matplotlib);\n"
    "      --jobs: OMPL's planners on one thread (@fcl, @gpu) run N at a time (default\n"
    "      1), one on each GPU: faster runs, but each slower than alone (the summary\n"
    "      says so): compare planners with 1; --gpus: the gpu groups use at most N of\n"
    "      the GPUs the machine shows (default all; CUDA_VISIBLE_DEVICES chooses which),\n"
    "      one GPU per worker, ours one per GPU at a time with a GPU's share of the\n"
    "      cores (results.csv's device column says which ran where); --threads: the\n"
    "      host threads of every group\n"
    "      (default: all cores for a group that runs alone, shared otherwise);\n"
    "      a path failing the re-check is kept in DIR/failed_paths/;\n"
    "      --save-baseline keeps the groups' figures, --baseline compares with them\n"
    "      (exit 5 on a regression beyond the configuration's tolerances); exit 3 when a\n"
    "      returned path fails the fine FCL re-check; --shard I/N runs only the I-th of\n"
    "      N shares of the scenes (or problems): every N-th from the I-th, keeping their\n"
    "      run numbers, so N shards on N machines or GPUs run the whole configuration\n"
    "      (their results.csv files joined, one header, make one run's); --report DIR\n"
    "      summarises an earlier run's folder again (and draws its plots) instead of\n"
    "      running\n"
    "Exit codes: 0 done, 1 internal error, 2 bad input or usage, 3 a path failed the FCL\n"
    "re-check, 5 a regression against the baseline; SIGINT or SIGTERM stops a run cleanly,\n"
    "keeping the runs done in DIR/results.partial.csv: exit 130 (SIGINT) or 143 (SIGTERM);\n"
    "a second signal ends it at once. `gplan bench CONFIG ...` is a deprecated alias.\n";

namespace {

namespace fs = std::filesystem;

// Exit codes beyond gplan's own (0 done, 1 internal error, 2 bad input or usage).
constexpr int kExitPathFailedRecheck = 3;  // a returned path failed the FCL re-check
constexpr int kExitRegression = 5;         // worse than the baseline beyond a tolerance

// --shard I/N: the I-th (1-based) of N shares of the configuration's scenes, every N-th
// from the I-th (a problem set lists its scenarios one after another, so each share
// takes from all of them).
void keep_shard(const std::string& shard, BenchConfig* config) {
  unsigned long i = 0, n = 0;
  char slash = 0, rest = 0;
  std::istringstream in(shard);
  const bool digits = !shard.empty() && std::isdigit(static_cast<unsigned char>(shard[0]));
  if (!digits || !(in >> i >> slash >> n) || slash != '/' || in.get(rest) || i < 1 || i > n ||
      n > 1000000)
    throw UsageError("--shard " + shard + ": give I/N, whole numbers with 1 <= I <= N (e.g. 2/4)");
  if (n > config->scenes.size())
    throw UsageError("--shard " + shard + ": " + config->file + " has " +
                     std::to_string(config->scenes.size()) + " scene(s) or problems, fewer than " +
                     std::to_string(n) + " shards; give at most " +
                     std::to_string(config->scenes.size()));
  BenchConfig kept = *config;
  kept.scenes.clear();
  kept.scene_labels.clear();
  kept.first_runs.clear();
  for (std::size_t s = i - 1; s < config->scenes.size(); s += n) {
    kept.scenes.push_back(config->scenes[s]);
    if (s < config->scene_labels.size()) kept.scene_labels.push_back(config->scene_labels[s]);
    if (s < config->first_runs.size()) kept.first_runs.push_back(config->first_runs[s]);
  }
  *config = kept;
}

std::string timestamp(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[64];
  std::strftime(text, sizeof text, format, &local);
  return text;
}

// The output folder must be a new one or an empty one, never a folder with files in it
// (an earlier run's results are not replaced), and it must be possible to make files
// there: checked before any work, the folder made only once the inputs have loaded (a
// refused run leaves nothing behind).
void check_output_folder(const std::string& dir) {
  if (dir.empty()) throw UsageError("--out: an empty name; name a new folder for the results");
  std::error_code error;
  if (fs::exists(fs::symlink_status(dir, error))) {
    if (!fs::is_directory(fs::status(dir, error)))
      throw UsageError("--out " + dir + ": is not a folder; name a new folder for the results");
    if (!fs::is_empty(dir, error))
      throw UsageError("--out " + dir +
                       ": the folder has files in it; name a new or empty folder "
                       "(the results of an earlier run are not replaced)");
    gplanner::writable_output_target("--out", (fs::path(dir) / "results.csv").string());
    return;
  }
  // A new folder (and any new folders above it): a file can be made in the nearest
  // existing one.
  fs::path existing = fs::absolute(dir, error).parent_path();
  while (!existing.empty() && !fs::exists(existing, error) && existing != existing.root_path())
    existing = existing.parent_path();
  gplanner::writable_output_target("--out", (existing / fs::path(dir).filename()).string());
}

void make_output_folder(const std::string& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error)
    throw UsageError("--out " + dir + ": cannot be made (" + error.message() +
                     "); name a folder that can be created");
}

// A folder of its own under the system's temporary folder, removed with its contents
// when it goes (none when `prefix` is empty).
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& prefix) {
    if (prefix.empty()) return;
    std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot make a scratch folder " + pattern + ": " + std::strerror(errno));
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A problem set's problems written as scene files into `folder`: the configuration's
// scenes, each named by its scenario, its runs numbered from the problem's index times
// the runs per problem.
void name_problem_scenes(const std::string& folder, BenchConfig* config) {
  const MotionBenchMakerSet& set = *config->problem_set;
  config->scenes = write_problem_scenes(set, folder);
  std::map<std::string, int> index;  // per scenario
  for (const MotionBenchMakerSet::Problem& p : set.problems) {
    config->scene_labels.push_back(p.scenario);
    config->first_runs.push_back(index[p.scenario]++ * config->runs);
  }
}

// A problem whose start or goal collides, as one record per planner (status "invalid",
// not run): counted, and said, in the summary.
void add_invalid_records(const BenchConfig& config, std::size_t s, const std::string& reason,
                         std::vector<BenchRecord>* out) {
  for (const PlannerChoice& choice : config.planners) {
    for (int run = 0; run < config.runs; ++run) {
      BenchRecord record;
      record.experiment = config.name;
      record.scene = config.scene_labels[s];
      record.planner = choice.planner;
      record.checker = choice.checker;
      record.run = config.first_runs[s] + run;
      record.seed = config.seed + static_cast<std::uint64_t>(run);
      record.status = "invalid";
      record.note = fs::path(config.scenes[s]).stem().string() + ": " + reason;
      out->push_back(record);
    }
  }
}

// The problem set's scene files kept in the output folder (problems/).
void keep_problem_scenes(const std::string& from, const std::string& dir) {
  const fs::path to = fs::path(dir) / "problems";
  fs::create_directories(to);
  for (const auto& entry : fs::directory_iterator(from))
    fs::copy_file(entry.path(), to / entry.path().filename(), fs::copy_options::overwrite_existing);
}

std::string csv_text(const std::vector<BenchRecord>& records) {
  std::ostringstream out;
  write_bench_csv_header(out);
  for (const BenchRecord& record : records) write_bench_csv_line(out, record);
  return out.str();
}

// Summary, verdicts and exit code of a run's records (a new run or --report).
int conclude(const BenchConfig& config, const std::vector<BenchRecord>& records,
             const std::string& dir, const std::string& baseline_file,
             const std::vector<GroupSummary>& baseline, const std::string& save_baseline,
             bool plots, const std::string& side_by_side = {}) {
  const std::vector<GroupSummary> groups = summarize(records);
  std::ostringstream summary;
  summary << "gplan bench " << config.name << " (" << config.kind << ")\n\n";
  if (!side_by_side.empty()) summary << "notice: " << side_by_side << "\n\n";
  print_summary(summary, groups);
  if (config.problem_set) print_problem_set_summary(summary, records);
  print_stage_summary(summary, records);
  std::map<long long, int> runs_by_device;  // where several GPUs ran the gpu groups
  for (const BenchRecord& r : records)
    if (r.device >= 0) ++runs_by_device[r.device];
  if (runs_by_device.size() > 1) {
    summary << "\nruns by GPU:";
    for (const auto& [device, runs] : runs_by_device)
      summary << (device == runs_by_device.begin()->first ? " " : ", ") << "device " << device
              << " " << runs;
    summary << "\n";
  }
  int failed_paths = 0;
  for (const GroupSummary& g : groups) failed_paths += g.path_failures;
  if (failed_paths) {
    summary << "\nFAILED: " << failed_paths << " returned path" << (failed_paths > 1 ? "s" : "")
            << " collide under the fine FCL re-check:\n";
    for (const BenchRecord& r : records) {
      if (r.path_check == "fail")
        summary << "  " << r.scene << " " << r.planner << "@" << r.checker << " run " << r.run
                << " (seed " << r.seed << "): " << r.note << "\n";
    }
  }
  bool regressed = false;
  if (!baseline_file.empty()) {
    const BaselineVerdict verdict = compare_with_baseline(groups, baseline, config.tolerances);
    regressed = verdict.regressed();
    summary << "\nagainst the baseline " << baseline_file << ": "
            << (regressed ? "REGRESSION" : "within tolerance") << "\n";
    for (const std::string& line : verdict.regressions) summary << "  regression: " << line << "\n";
    for (const std::string& line : verdict.notes) summary << "  note: " << line << "\n";
  }
  std::istringstream lines(summary.str());
  for (std::string line; std::getline(lines, line);)
    std::cout << gplanner::terminal_text(line) << "\n";
  std::cout << std::flush;
  write_text((fs::path(dir) / "summary.txt").string(), summary.str());
  if (!save_baseline.empty()) {
    gplan::save_baseline(save_baseline, config.file, groups);
    std::cerr << "baseline saved: " << save_baseline << "\n";
  }
  if (plots) {
    std::string notice;
    const std::string plot_dir = (fs::path(dir) / "plots").string();  // made by the script
    if (draw_bench_plots((fs::path(dir) / "results.csv").string(), plot_dir, &notice)) {
      std::cerr << "plots: " << plot_dir << "\n";
    } else {
      std::cerr << "notice: no plots: " << gplanner::terminal_text(notice) << "\n";
    }
  }
  if (failed_paths) return kExitPathFailedRecheck;
  return regressed ? kExitRegression : 0;
}

}  // namespace

int run_bench(int argc, char** argv) {
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << kBenchUsage;
    return 0;
  }
  catch_interruptions();
  const std::function<bool()> should_stop = [] { return interrupted(); };
  // -o DIR is --out DIR.
  std::vector<std::string> words(argv, argv + argc);
  for (std::string& word : words)
    if (word == "-o") word = "--out";
  std::vector<char*> args_v;
  for (std::string& word : words) args_v.push_back(word.data());
  const CommandLine args(
      int(args_v.size()), args_v.data(), 1,
      {"out", "jobs", "gpus", "threads", "baseline", "save-baseline", "report", "shard"},
      {"no-plots"});
  if (args.positionals().size() != 1)
    throw UsageError("gplan-bench takes one configuration file (benchmarks/config/*.yaml), not " +
                     std::to_string(args.positionals().size()) + "; give exactly one");
  const std::string config_file = args.positionals()[0];
  const int jobs = static_cast<int>(args.count("jobs", 1, 1, 1024));
  const int max_gpus = static_cast<int>(args.count("gpus", 1024, 1, 1024));
  const int threads = static_cast<int>(args.count("threads", 0, 1, gplanner::kMaxThreads));
  const std::string baseline = args.text("baseline", "");
  const std::string save = args.text("save-baseline", "");
  const bool report = args.has("report");
  if (report && args.has("out"))
    throw UsageError("--report DIR reads an earlier run's folder; leave out --out");
  if (report && args.has("shard"))
    throw UsageError("--report DIR summarises the records in DIR/results.csv; leave out --shard");

  // Inputs and outputs checked before any work.
  std::vector<gplanner::NamedFile> inputs{{"the configuration", config_file}};
  if (!baseline.empty()) inputs.push_back({"the --baseline file", baseline});
  std::vector<gplanner::NamedFile> outputs;
  if (!save.empty()) outputs.push_back({"--save-baseline", save});
  gplanner::check_output_paths(outputs, inputs);
  BenchConfig config = load_bench_config(config_file);
  if (config.kind == "error-time" || config.kind == "broad-phase") {
    for (const char* option :
         {"baseline", "save-baseline", "report", "jobs", "gpus", "threads", "shard"}) {
      if (args.has(option))
        throw UsageError(std::string("--") + option + " does not apply to the " + config.kind +
                         " study (" + config_file + "); leave it out");
    }
  }
  std::vector<GroupSummary> baseline_groups;  // its errors now, not after the runs
  if (!baseline.empty()) baseline_groups = load_baseline(baseline);

  if (report) {
    const std::string dir = args.text("report", "");
    const std::string csv = (fs::path(dir) / "results.csv").string();
    gplanner::check_input_file(csv, {"bench results", 1024 * gplanner::kMiB}, {"--report", 0, ""});
    std::vector<BenchRecord> records;
    try {
      records = read_bench_csv(csv);
    } catch (const std::runtime_error& e) {
      throw gplanner::InputError({"--report", 0, ""}, std::string(e.what()) +
                                                          "; name the folder of a gplan-bench run, "
                                                          "its results.csv as gplan-bench wrote it");
    }
    return conclude(config, records, dir, baseline, baseline_groups, save, !args.flag("no-plots"));
  }

  const std::string dir =
      args.text("out", "gplan-bench-" + config.name + "-" + timestamp("%Y%m%d-%H%M%S"));
  // A problem set's problems as scene files, in a scratch folder until the output folder
  // is made (they are kept there, in problems/).
  const ScratchFolder generated(config.problem_set ? "gplan-bench-problems" : "");
  if (config.problem_set) name_problem_scenes(generated.path(), &config);
  if (args.has("shard")) keep_shard(args.text("shard", ""), &config);
  for (const auto& scene : config.scenes) inputs.push_back({"a scene of the configuration", scene});
  gplanner::check_output_paths(outputs, inputs);
  check_output_folder(dir);
  if (config.kind == "broad-phase") {  // no scenes: its spheres are generated
    make_output_folder(dir);
    return run_broad_phase_study(config, dir, !args.flag("no-plots"), should_stop);
  }

  // Scenes loaded once, before the workers are forked (they share them).
  const auto start = std::chrono::steady_clock::now();
  std::vector<gplanner::Scene> scenes;
  std::vector<BenchRecord> invalid;  // a problem set's problems not run
  BenchConfig valid = config;
  valid.scenes.clear();
  valid.scene_labels.clear();
  valid.first_runs.clear();
  std::set<std::string> noticed;
  for (std::size_t s = 0; s < config.scenes.size(); ++s) {
    const std::string& file = config.scenes[s];
    if (!config.problem_set) std::cerr << "loading " << file << "\n";
    scenes.push_back(gplanner::load_scene(file));
    for (const std::string& notice : scenes.back().notices)
      if (noticed.insert(notice).second)
        std::cerr << "notice: " << gplanner::terminal_text(notice) << "\n";
    if (config.kind != "queries") {  // planning, and the study's planning curves
      // A start or goal in collision is the scene's error, said once now (exit 2), not
      // a failed run in every group; a problem set's problem is counted invalid instead.
      gplanner::FclChecker fcl(scenes.back(), /*threads=*/1);
      try {
        gplanner::check_start_and_goal(scenes.back(), &fcl);
      } catch (const gplanner::InputError& e) {
        if (!config.problem_set) throw;
        scenes.pop_back();
        add_invalid_records(config, s, e.what(), &invalid);
        continue;
      }
    }
    valid.scenes.push_back(file);
    if (s < config.scene_labels.size()) {
      valid.scene_labels.push_back(config.scene_labels[s]);
      valid.first_runs.push_back(config.first_runs[s]);
    }
    if (should_stop()) return report_interruption({}, {"--out " + dir});
  }
  if (config.problem_set) {
    std::cerr << "loaded " << config.scenes.size() << " problems of " << config.problem_set->folder
              << ": " << valid.scenes.size() << " valid, " << config.scenes.size() - valid.scenes.size()
              << " with the start or goal in collision\n";
  }
  config = valid;
  make_output_folder(dir);
  if (config.problem_set) keep_problem_scenes(generated.path(), dir);
  if (config.kind == "error-time")
    return run_error_time_study(config, scenes, dir, !args.flag("no-plots"), should_stop);
  const std::vector<BenchGroup> groups = bench_groups(config);
  BenchResources resources;
  resources.jobs = jobs;
  resources.threads = threads;
  if (std::any_of(groups.begin(), groups.end(), [](const BenchGroup& g) { return g.gpu; })) {
    const int visible = count_gpus_in_child();
    resources.gpus = std::max(1, std::min(max_gpus, visible));
    if (visible > 1 || args.has("gpus")) {
      std::cerr << "GPUs: " << resources.gpus << " of the " << visible << " this machine shows"
                << (args.has("gpus") && max_gpus > visible
                        ? " (--gpus " + std::to_string(max_gpus) + " asked for more)"
                        : std::string())
                << "\n";
    }
  }
  const std::string started = local_date_time();
  // Each record also goes to results.partial.csv as it comes, so that the runs done are
  // kept when the benchmark is interrupted or killed; results.csv replaces it at the end.
  const std::string partial = (fs::path(dir) / "results.partial.csv").string();
  std::ofstream partial_csv(partial);
  write_bench_csv_header(partial_csv);
  std::vector<BenchRecord> records = run_bench_groups(
      config, scenes, groups, resources, std::cerr, should_stop,
      [&](const BenchRecord& record) {
        write_bench_csv_line(partial_csv, record);
        partial_csv.flush();
      },
      (fs::path(dir) / "failed_paths").string());
  for (const BenchRecord& record : invalid) write_bench_csv_line(partial_csv, record);
  partial_csv.close();
  if (should_stop()) return report_interruption({partial + " (the runs done)"}, {});
  records.insert(records.end(), invalid.begin(), invalid.end());
  const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  write_text((fs::path(dir) / "results.csv").string(), csv_text(records));
  write_config_copy(dir, config_file);
  if (config.kind == "planning") {
    fs::create_directories(fs::path(dir) / "ompl");
    std::vector<std::string> names;  // the records' scenes (a problem set's scenarios)
    for (const BenchRecord& r : records)
      if (std::find(names.begin(), names.end(), r.scene) == names.end()) names.push_back(r.scene);
    for (const std::string& name : names) {
      std::vector<BenchRecord> scene_records;
      for (const BenchRecord& r : records)  // a problem not run has no place in OMPL's log
        if (r.scene == name && r.status != "invalid") scene_records.push_back(r);
      OmplLogExperiment experiment;
      experiment.host = ompl_host_name();
      experiment.cpu_info = ompl_cpu_info();
      experiment.name = config.name + "." + name;  // one word: the reader keeps the last
      experiment.setup = "gplan bench " + config.file + "\nscene " + name;
      experiment.date = started;
      experiment.seed = config.seed;
      experiment.time_limit_s = config.time_limit_s;
      experiment.memory_limit_mb = 0;
      experiment.total_seconds = total;
      experiment.runs_per_planner = config.runs;
      if (config.problem_set && !scene_records.empty()) {  // its problems x config.runs
        int runs = 0;
        for (const BenchRecord& r : scene_records)
          runs += r.planner == scene_records.front().planner &&
                  r.checker == scene_records.front().checker;
        experiment.runs_per_planner = runs;
      }
      write_ompl_log_file((fs::path(dir) / "ompl" / (name + ".log")).string(), experiment,
                          scene_records);
    }
  }
  fs::remove(partial);
  std::cerr << "results: " << dir << "\n";
  return conclude(config, records, dir, baseline, baseline_groups, save, !args.flag("no-plots"),
                  side_by_side_notice(groups, jobs));
}

}  // namespace gplan

#pragma once
// A `gplan-bench` configuration (YAML, benchmarks/config/*.yaml): what to run, how often, and
// the tolerances of the verdict against a baseline. See benchmarks/README.md for the keys.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harness/broad_phase_config.h"
#include "harness/error_time_config.h"
#include "harness/motionbenchmaker.h"

namespace gplan {

// One planner with one checker, written "PLANNER@CHECKER" in a configuration:
// ours-lazyprm@gpu, ompl-rrtconnect@fcl (OMPL's planner as its users run it: our FCL
// backend on the planning thread, OMPL's DiscreteMotionValidator), ompl-prm@gpu (OMPL's
// planner with our validity checker and motion validator: the OMPL plugin).
struct PlannerChoice {
  std::string planner;  // bench_planners(): ours-auto, ours-lazyprm, ..., ompl-lazyprm
  // gpu, cpu, fcl; for OMPL's planners through the plugin also gpu-sampled, cpu-sampled:
  // the plugin's motion validator sampled, not certified (its default).
  std::string checker;
  std::string label() const { return planner + "@" + checker; }
  bool ours() const { return planner.rfind("ours-", 0) == 0; }
  // The collision backend the checker names (gpu, cpu, fcl).
  std::string backend() const { return checker.substr(0, checker.find('-')); }
  bool sampled() const { return checker.find("-sampled") != std::string::npos; }
  // OMPL's planner with FCL, or with the gpu plugin: one planning thread, so several may
  // run at once (those on the GPU one at a time).
  bool single_threaded() const { return !ours() && (backend() == "fcl" || backend() == "gpu"); }
};

// Regression tolerances: a group of the run is a regression against the same group of
// the baseline when its median time exceeds time_ratio times the baseline's (and the
// difference exceeds time_floor_s), its success rate falls more than success_rate below
// the baseline's, or its median path length exceeds path_length_ratio times the
// baseline's.
struct BenchTolerances {
  double time_ratio = 1.5;
  double time_floor_s = 0.05;
  double success_rate = 0.2;
  double path_length_ratio = 1.25;
};

struct BenchConfig {
  std::string file;                 // where it was read from
  std::string name;                 // the experiment's name
  std::string kind;                 // "planning", "queries", "error-time" or "broad-phase"
  std::vector<std::string> scenes;  // scene files, resolved against the config's folder (none
                                    // for broad-phase; a problem set's once written)
  // planning on a MotionBenchMaker problem set instead of scenes (motionbenchmaker.h)
  std::optional<MotionBenchMakerSet> problem_set;
  // Per scene, the name its records carry and the run number of its first run (by
  // default the file's stem and 0; a problem set's: the scenario and the problem's index).
  std::vector<std::string> scene_labels;
  std::vector<int> first_runs;
  // planning
  std::vector<PlannerChoice> planners;
  int runs = 10;
  double time_limit_s = 30;
  // No new run of a (scene, planner) group starts after the group has spent this long
  // (0: no bound); the runs it leaves out are counted as not run, not as failures.
  double group_budget_s = 0;
  // The fine re-check of every returned path: FCL at 1/refinement of the scene's edge
  // resolution (and of its max_displacement, when set).
  double recheck_refinement = 10;
  bool simplify = true;  // OMPL's planners: simplifySolution after a solve, timed apart
  // queries
  std::vector<std::string> tables;    // collision-queries, local-planning
  std::vector<std::string> checkers;  // gpu-basic, gpu-packet, gpu-balanced, cpu, fcl
  std::uint64_t queries = 50000;
  std::uint64_t milestones = 10000;
  int neighbors = 15;
  int repeat = 5;
  // error-time (the error-against-time study)
  ErrorTimeOptions error_time;
  // broad-phase (the sphere broad-phase study)
  BroadPhaseOptions broad_phase;
  // all kinds
  std::uint64_t seed = 1;  // run i (from 0) of every group uses seed + i
  BenchTolerances tolerances;
};

// Reads and checks a configuration; throws gplanner::InputError naming the file, line
// and key, what is wrong and what to change. Scene files are checked to exist (not
// loaded).
BenchConfig load_bench_config(const std::string& file);

// The planner and checker names a planning configuration accepts (the query tables':
// query_tables() and query_table_checkers(), bench/query_runs.h).
const std::vector<std::string>& bench_planners();
const std::vector<std::string>& bench_plan_checkers();

// Why a group asking for a gpu checker is left out where the gpu backend would run on
// the cpu instead (`notice`: the fallback's reason): its times would be the cpu's under a
// gpu name.
std::string fallback_refusal(const std::string& checker, const std::string& notice);

}  // namespace gplan

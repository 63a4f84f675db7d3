#include "bench_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "harness/query_runs.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/yaml_reader.h"
#include "gplanner/planner/scene/yaml_structure.h"

namespace gplan {
namespace {

using gplanner::InputError;
using gplanner::YamlReader;

inline constexpr gplanner::InputFileKind kBenchConfigFile{"bench configuration", gplanner::kMiB};

std::string listed(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// A list of names, each one of `allowed`, none twice, at least one.
std::vector<std::string> names(const YamlReader& in, const YAML::Node& node, const std::string& key,
                               const std::vector<std::string>& allowed, const std::string& what) {
  if (!node.IsSequence() || node.size() == 0)
    in.fail(node, key, "expected a list of " + what + " (one or more of: " + listed(allowed) + ")");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item_key = key + "[" + std::to_string(i) + "]";
    const std::string name = in.text(node[i], item_key);
    if (!allowed.empty() && !contains(allowed, name))
      in.fail(node[i], item_key, "'" + name + "' is not one of " + listed(allowed));
    if (contains(out, name))
      in.fail(node[i], item_key, "'" + name + "' is listed twice; list it once");
    out.push_back(name);
  }
  return out;
}

double positive(const YamlReader& in, const YAML::Node& node, const std::string& key, double high) {
  const double value = in.number(node, key);
  if (!(value > 0) || value > high) {
    in.fail(node, key,
            "expected a number above 0 and at most " + std::to_string(high) + ", found '" +
                node.Scalar() + "'");
  }
  return value;
}

BenchTolerances read_tolerances(const YamlReader& in, const YAML::Node& node) {
  BenchTolerances t;
  if (!node) return t;
  in.expect_map(node, "tolerances",
                {"time_ratio", "time_floor", "success_rate", "path_length_ratio"});
  if (node["time_ratio"]) {
    t.time_ratio = in.number(node["time_ratio"], "tolerances.time_ratio");
    if (!(t.time_ratio >= 1))
      in.fail(node["time_ratio"], "tolerances.time_ratio",
              "must be at least 1 (1.5: 50 % slower is a regression)");
  }
  if (node["time_floor"]) {
    t.time_floor_s = in.number(node["time_floor"], "tolerances.time_floor");
    if (!(t.time_floor_s >= 0))
      in.fail(node["time_floor"], "tolerances.time_floor", "must be 0 or more seconds");
  }
  if (node["success_rate"]) {
    t.success_rate = in.number(node["success_rate"], "tolerances.success_rate");
    if (!(t.success_rate >= 0 && t.success_rate <= 1))
      in.fail(node["success_rate"], "tolerances.success_rate",
              "must be from 0 to 1 (the drop in the fraction of runs solved)");
  }
  if (node["path_length_ratio"]) {
    t.path_length_ratio = in.number(node["path_length_ratio"], "tolerances.path_length_ratio");
    if (!(t.path_length_ratio >= 1))
      in.fail(node["path_length_ratio"], "tolerances.path_length_ratio", "must be at least 1");
  }
  return t;
}

}  // namespace

const std::vector<std::string>& bench_planners() {
  static const std::vector<std::string> planners = {
      "ours-auto",       "ours-lazyprm", "ours-prm",    "ours-rrtconnect",
      "ompl-rrtconnect", "ompl-prm",     "ompl-lazyprm"};
  return planners;
}

const std::vector<std::string>& bench_plan_checkers() {
  static const std::vector<std::string> checkers = {"gpu", "cpu", "fcl", "gpu-sampled",
                                                    "cpu-sampled"};
  return checkers;
}

std::string fallback_refusal(const std::string& checker, const std::string& notice) {
  return "no GPU can be used here (" + notice + "); " + checker +
         " is left out rather than timing the cpu backend under its name: measure cpu by its "
         "own name, or run where there is a GPU";
}

BenchConfig load_bench_config(const std::string& file) {
  const YAML::Node root = gplanner::load_checked_yaml(file, kBenchConfigFile, "");
  const YamlReader in(file);
  BenchConfig config;
  config.file = file;
  std::set<std::string> keys = {"name",       "kind",       "scenes",       "planners",
                                "runs",       "time_limit", "group_budget", "recheck_refinement",
                                "simplify",   "tables",     "checkers",     "queries",
                                "milestones", "neighbors",  "repeat",       "seed",
                                "tolerances", "motionbenchmaker"};
  keys.insert(error_time_keys().begin(), error_time_keys().end());
  keys.insert(broad_phase_keys().begin(), broad_phase_keys().end());
  in.expect_map(root, "", keys);
  config.name =
      root["name"] ? in.text(root["name"], "name") : std::filesystem::path(file).stem().string();
  if (config.name.empty() || config.name.find_first_of("\n\r") != std::string::npos)
    in.fail(root["name"], "name", "must be one line of text");
  config.kind = in.text(in.required(root, "", "kind"), "kind");
  if (config.kind != "planning" && config.kind != "queries" && config.kind != "error-time" &&
      config.kind != "broad-phase") {
    in.fail(root["kind"], "kind",
            "'" + config.kind + "' is not one of planning, queries, error-time, broad-phase");
  }
  const bool broad_phase = config.kind == "broad-phase";
  if (broad_phase && root["scenes"]) {
    in.fail(root["scenes"], "scenes",
            "does not apply to kind: broad-phase (its spheres are generated); remove it");
  }

  // A planning configuration names scenes, or a MotionBenchMaker problem set.
  const bool problem_set = config.kind == "planning" && root["motionbenchmaker"];
  if (root["motionbenchmaker"] && config.kind != "planning")
    in.fail(root["motionbenchmaker"], "motionbenchmaker", "applies to kind: planning only; remove it");
  if (problem_set && root["scenes"])
    in.fail(root["scenes"], "scenes", "give scenes or motionbenchmaker, not both");
  if (problem_set)
    config.problem_set = read_motionbenchmaker(in, root["motionbenchmaker"], file);
  const YAML::Node scenes = broad_phase || problem_set ? YAML::Node(YAML::NodeType::Sequence)
                                                       : in.required(root, "", "scenes");
  for (const std::string& scene :
       broad_phase || problem_set ? std::vector<std::string>{}
                                  : names(in, scenes, "scenes", {}, "scene files")) {
    const std::size_t i = config.scenes.size();
    const std::string resolved =
        (std::filesystem::path(file).parent_path() / scene).lexically_normal().string();
    gplanner::check_input_file(resolved, gplanner::kSceneFile,
                               in.at(scenes[i], "scenes[" + std::to_string(i) + "]"));
    config.scenes.push_back(resolved);
  }
  std::set<std::string> stems;
  for (std::size_t i = 0; i < config.scenes.size(); ++i) {
    const std::string stem = std::filesystem::path(config.scenes[i]).stem().string();
    if (!stems.insert(stem).second) {
      in.fail(scenes[i], "scenes[" + std::to_string(i) + "]",
              "two scenes are named '" + stem +
                  "' (the file name without .yaml names a scene "
                  "in the results); rename one file");
    }
  }

  // Keys of the other kind are refused rather than ignored.
  const std::vector<std::string> planning_keys = {
      "planners", "runs", "time_limit", "group_budget", "recheck_refinement", "simplify"};
  const std::vector<std::string> query_keys = {"tables",     "checkers",  "queries",
                                               "milestones", "neighbors", "repeat"};
  const std::vector<std::string>& own_keys = config.kind == "planning"     ? planning_keys
                                             : config.kind == "queries"    ? query_keys
                                             : config.kind == "error-time" ? error_time_keys()
                                                                           : broad_phase_keys();
  // (The studies have no baseline, so no tolerances either.)
  const bool study = config.kind == "error-time" || broad_phase;
  for (const std::string& key : keys) {
    if (!root[key] || contains(own_keys, key)) continue;
    if (contains(planning_keys, key) || contains(query_keys, key) ||
        contains(error_time_keys(), key) || contains(broad_phase_keys(), key) ||
        (key == "tolerances" && study))
      in.fail(root[key], key, "does not apply to kind: " + config.kind + "; remove it");
  }

  if (config.kind == "error-time") {
    config.error_time = read_error_time_options(in, root);
  } else if (broad_phase) {
    config.broad_phase = read_broad_phase_options(in, root);
  } else if (config.kind == "planning") {
    const YAML::Node planners = in.required(root, "", "planners");
    for (const std::string& label : names(in, planners, "planners", {}, "PLANNER@CHECKER names")) {
      const std::size_t i = config.planners.size();
      const std::size_t at = label.find('@');
      PlannerChoice choice{label.substr(0, at),
                           at == std::string::npos ? "" : label.substr(at + 1)};
      if (at == std::string::npos || !contains(bench_planners(), choice.planner) ||
          !contains(bench_plan_checkers(), choice.checker)) {
        in.fail(planners[i], "planners[" + std::to_string(i) + "]",
                "'" + label + "' is not PLANNER@CHECKER with PLANNER one of " +
                    listed(bench_planners()) + " and CHECKER one of " +
                    listed(bench_plan_checkers()) + " (e.g. ompl-rrtconnect@fcl)");
      }
      if (choice.sampled() && choice.ours()) {
        in.fail(planners[i], "planners[" + std::to_string(i) + "]",
                "'" + label +
                    "': -sampled names the plugin's sampled motion validator, for "
                    "OMPL's planners; ours are given by --edges (sampled edges, a certified path)");
      }
      config.planners.push_back(choice);
    }
    if (root["runs"]) config.runs = int(in.whole_number(root["runs"], "runs", 1, 100000));
    if (root["time_limit"])
      config.time_limit_s = positive(in, root["time_limit"], "time_limit", 86400);
    if (root["group_budget"])
      config.group_budget_s = positive(in, root["group_budget"], "group_budget", 1e7);
    if (root["recheck_refinement"]) {
      config.recheck_refinement =
          double(in.whole_number(root["recheck_refinement"], "recheck_refinement", 1, 1000));
    }
    if (root["simplify"]) {
      const std::string value = in.text(root["simplify"], "simplify");
      if (value != "true" && value != "false")
        in.fail(root["simplify"], "simplify", "expected true or false, found '" + value + "'");
      config.simplify = value == "true";
    }
  } else {
    config.tables = names(in, in.required(root, "", "tables"), "tables", query_tables(), "tables");
    config.checkers = names(in, in.required(root, "", "checkers"), "checkers",
                            query_table_checkers(), "checkers");
    if (root["queries"]) config.queries = in.whole_number(root["queries"], "queries", 1, 100000000);
    if (root["milestones"])
      config.milestones = in.whole_number(root["milestones"], "milestones", 2, 10000000);
    if (root["neighbors"])
      config.neighbors = int(in.whole_number(root["neighbors"], "neighbors", 1, 1000));
    if (root["repeat"]) config.repeat = int(in.whole_number(root["repeat"], "repeat", 1, 1000));
  }
  if (root["seed"]) config.seed = in.whole_number(root["seed"], "seed", 1, 4000000000ULL);
  config.tolerances = read_tolerances(in, root["tolerances"]);
  return config;
}

}  // namespace gplan

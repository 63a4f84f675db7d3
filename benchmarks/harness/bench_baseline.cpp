#include "bench_baseline.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/yaml_reader.h"
#include "gplanner/planner/scene/yaml_structure.h"

namespace gplan {
namespace {

inline constexpr gplanner::InputFileKind kBaselineFile{"baseline", 64 * gplanner::kMiB};
inline constexpr int kBaselineFormat = 1;

std::string figure(double value) {
  std::ostringstream text;
  text << std::setprecision(4) << value;
  return text.str();
}

}  // namespace

void save_baseline(const std::string& file, const std::string& config_file,
                   const std::vector<GroupSummary>& groups) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "gplan_bench_baseline" << YAML::Value << kBaselineFormat;
  out << YAML::Key << "config" << YAML::Value << config_file;
  out << YAML::Key << "groups" << YAML::Value << YAML::BeginSeq;
  for (const GroupSummary& g : groups) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "experiment" << YAML::Value << g.experiment;
    out << YAML::Key << "scene" << YAML::Value << g.scene;
    out << YAML::Key << "planner" << YAML::Value << g.planner;
    out << YAML::Key << "checker" << YAML::Value << g.checker;
    out << YAML::Key << "runs" << YAML::Value << g.runs;
    out << YAML::Key << "success_rate" << YAML::Value << figure(g.success_rate);
    out << YAML::Key << "median_time_s" << YAML::Value << figure(g.median_time_s);
    if (std::isfinite(g.median_length))
      out << YAML::Key << "median_length" << YAML::Value << figure(g.median_length);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  gplanner::write_file_atomically(file, [&](std::ostream& text) { text << out.c_str() << "\n"; });
}

std::vector<GroupSummary> load_baseline(const std::string& file) {
  const YAML::Node root = gplanner::load_checked_yaml(file, kBaselineFile, "");
  const gplanner::YamlReader in(file);
  in.expect_map(root, "", {"gplan_bench_baseline", "config", "groups"});
  const YAML::Node format = in.required(root, "", "gplan_bench_baseline");
  if (in.number(format, "gplan_bench_baseline") != kBaselineFormat) {
    in.fail(format, "gplan_bench_baseline",
            "format " + format.Scalar() + " is not the one this gplan reads (" +
                std::to_string(kBaselineFormat) + "); save the baseline again");
  }
  const YAML::Node groups = in.required(root, "", "groups");
  if (!groups.IsSequence()) in.fail(groups, "groups", "expected a list of groups");
  std::vector<GroupSummary> out;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const std::string key = "groups[" + std::to_string(i) + "]";
    const YAML::Node g = groups[i];
    in.expect_map(g, key,
                  {"experiment", "scene", "planner", "checker", "runs", "success_rate",
                   "median_time_s", "median_length"});
    GroupSummary s;
    s.experiment = g["experiment"] ? in.text(g["experiment"], key + ".experiment") : "";
    s.scene = in.text(in.required(g, key, "scene"), key + ".scene");
    s.planner = in.text(in.required(g, key, "planner"), key + ".planner");
    s.checker = in.text(in.required(g, key, "checker"), key + ".checker");
    s.runs = int(in.number(in.required(g, key, "runs"), key + ".runs"));
    s.success_rate = in.number(in.required(g, key, "success_rate"), key + ".success_rate");
    s.median_time_s = in.number(in.required(g, key, "median_time_s"), key + ".median_time_s");
    s.median_length = g["median_length"] ? in.number(g["median_length"], key + ".median_length")
                                         : std::nan("");
    if (!(s.success_rate >= 0 && s.success_rate <= 1))
      in.fail(g["success_rate"], key + ".success_rate", "must be from 0 to 1");
    if (!(s.median_time_s >= 0)) in.fail(g["median_time_s"], key + ".median_time_s", "must be 0 or more");
    out.push_back(s);
  }
  return out;
}

BaselineVerdict compare_with_baseline(const std::vector<GroupSummary>& run,
                                      const std::vector<GroupSummary>& baseline,
                                      const BenchTolerances& t) {
  BaselineVerdict verdict;
  std::map<std::string, const GroupSummary*> now;
  for (const GroupSummary& g : run) now[g.key()] = &g;
  std::map<std::string, bool> compared;
  for (const GroupSummary& base : baseline) {
    const auto found = now.find(base.key());
    if (found == now.end()) {
      verdict.regressions.push_back(base.key() + ": in the baseline, not in this run (run the same "
                                    "configuration, or save a new baseline)");
      continue;
    }
    compared[base.key()] = true;
    const GroupSummary& g = *found->second;
    if (g.median_time_s > t.time_ratio * base.median_time_s &&
        g.median_time_s - base.median_time_s > t.time_floor_s) {
      verdict.regressions.push_back(
          g.key() + ": median time " + figure(g.median_time_s) + " s against the baseline's " +
          figure(base.median_time_s) + " s (" + figure(g.median_time_s / base.median_time_s) +
          "x; tolerance " + figure(t.time_ratio) + "x)");
    }
    if (g.success_rate < base.success_rate - t.success_rate - 1e-9) {
      verdict.regressions.push_back(g.key() + ": success rate " + figure(g.success_rate) +
                                    " against the baseline's " + figure(base.success_rate) +
                                    " (tolerance " + figure(t.success_rate) + " lower)");
    }
    if (std::isfinite(g.median_length) && std::isfinite(base.median_length) &&
        g.median_length > t.path_length_ratio * base.median_length) {
      verdict.regressions.push_back(g.key() + ": median path length " + figure(g.median_length) +
                                    " against the baseline's " + figure(base.median_length) +
                                    " (tolerance " + figure(t.path_length_ratio) + "x)");
    }
  }
  for (const GroupSummary& g : run) {
    if (!compared.count(g.key())) verdict.notes.push_back(g.key() + ": no baseline to compare with");
  }
  return verdict;
}

}  // namespace gplan

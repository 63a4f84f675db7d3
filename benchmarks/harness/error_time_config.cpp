#include "harness/error_time_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gplanner/planner/scene/yaml_reader.h"

namespace gplan {
namespace {

using gplanner::YamlReader;

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// A list of numbers, each in (low, high] (or [low, high] when `low_closed`), whole where
// `whole_numbers`, none twice, at least one.
std::vector<double> numbers(const YamlReader& in, const YAML::Node& node, const std::string& key,
                            double low, bool low_closed, double high, bool whole_numbers,
                            const std::string& what) {
  if (!node.IsSequence() || node.size() == 0)
    in.fail(node, key, "expected a list of " + what + ", e.g. [" + number_text(high) + "]");
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item_key = key + "[" + std::to_string(i) + "]";
    const double value = in.number(node[i], item_key);
    const bool above = low_closed ? value >= low : value > low;
    if (!above || !(value <= high) || (whole_numbers && value != std::floor(value))) {
      in.fail(node[i], item_key,
              "expected " + std::string(whole_numbers ? "a whole number" : "a number") +
                  (low_closed ? " from " : " above ") + number_text(low) + " to " +
                  number_text(high) + " (" + what + "), found '" + node[i].Scalar() + "'");
    }
    if (std::find(out.begin(), out.end(), value) != out.end())
      in.fail(node[i], item_key, "'" + node[i].Scalar() + "' is listed twice; list it once");
    out.push_back(value);
  }
  return out;
}

// A list of checkers (gpu, cpu, fcl), each once; `required`: at least one.
std::vector<std::string> read_checkers(const YamlReader& in, const YAML::Node& checkers,
                                       const std::string& name, bool required) {
  if (!checkers.IsSequence() || (required && checkers.size() == 0))
    in.fail(checkers, name, "expected a list of checkers (one or more of: gpu, cpu, fcl)");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < checkers.size(); ++i) {
    const std::string key = name + "[" + std::to_string(i) + "]";
    const std::string checker = in.text(checkers[i], key);
    if (checker != "gpu" && checker != "cpu" && checker != "fcl")
      in.fail(checkers[i], key, "'" + checker + "' is not one of gpu, cpu, fcl");
    if (std::find(out.begin(), out.end(), checker) != out.end())
      in.fail(checkers[i], key, "'" + checker + "' is listed twice; list it once");
    out.push_back(checker);
  }
  return out;
}

}  // namespace

const std::vector<std::string>& error_time_keys() {
  static const std::vector<std::string> keys = {"checkers",
                                                "plan_checkers",
                                                "states",
                                                "edges",
                                                "roadmap_milestones",
                                                "edge_resolutions",
                                                "certified_steps",
                                                "truth_step",
                                                "deltas",
                                                "plan_milestones",
                                                "runs",
                                                "time_limit",
                                                "repeat"};
  return keys;
}

ErrorTimeOptions read_error_time_options(const YamlReader& in, const YAML::Node& root) {
  ErrorTimeOptions options;
  options.checkers = read_checkers(in, in.required(root, "", "checkers"), "checkers", true);
  options.plan_checkers = options.checkers;
  if (root["plan_checkers"]) {
    options.plan_checkers = read_checkers(in, root["plan_checkers"], "plan_checkers", false);
    for (std::size_t i = 0; i < options.plan_checkers.size(); ++i) {
      const std::string& c = options.plan_checkers[i];
      if (std::find(options.checkers.begin(), options.checkers.end(), c) == options.checkers.end())
        in.fail(root["plan_checkers"][i], "plan_checkers[" + std::to_string(i) + "]",
                "'" + c + "' is not in checkers; add it there or leave it out here");
    }
  }
  if (root["states"]) options.states = in.whole_number(root["states"], "states", 1, 100000000);
  if (root["edges"]) options.edges = in.whole_number(root["edges"], "edges", 1, 10000000);
  if (root["roadmap_milestones"]) {
    options.roadmap_milestones =
        in.whole_number(root["roadmap_milestones"], "roadmap_milestones", 2, 10000000);
  }
  if (root["edge_resolutions"]) {
    options.edge_resolutions =
        numbers(in, root["edge_resolutions"], "edge_resolutions", 0, false, 1000, false,
                "factors of the scene's edge resolution: 2 twice as coarse, 0.5 twice as fine");
  }
  if (root["certified_steps"]) {
    options.certified_steps =
        numbers(in, root["certified_steps"], "certified_steps", 0, false, 1, false,
                "first steps as fractions of the longest motion of the scene's space");
  }
  if (root["truth_step"]) {
    options.truth_step = in.number(root["truth_step"], "truth_step");
    if (!(options.truth_step > 0 && options.truth_step <= 1)) {
      in.fail(root["truth_step"], "truth_step",
              "expected a number above 0 and at most 1 (a fraction of the longest motion), "
              "found '" +
                  root["truth_step"].Scalar() + "'");
    }
  }
  const double smallest_step =
      *std::min_element(options.certified_steps.begin(), options.certified_steps.end());
  if (!(options.truth_step <= smallest_step)) {
    const YAML::Node at = root["truth_step"] ? root["truth_step"] : root["certified_steps"];
    in.fail(at, root["truth_step"] ? "truth_step" : "certified_steps",
            "the ground truth's step " + number_text(options.truth_step) +
                " must be at most the smallest certified step (" + number_text(smallest_step) +
                "); make truth_step smaller or the steps larger");
  }
  if (root["deltas"]) {
    options.deltas = numbers(in, root["deltas"], "deltas", 0, false, 1e-5, false,
                             "planner.delta_fraction values, within (0, 1e-5]");
  }
  if (root["plan_milestones"]) {
    options.plan_milestones = numbers(in, root["plan_milestones"], "plan_milestones", 2, true, 1e7,
                                      true, "first-round milestone counts");
  }
  if (root["runs"]) options.runs = int(in.whole_number(root["runs"], "runs", 1, 100000));
  if (root["time_limit"]) {
    options.time_limit_s = in.number(root["time_limit"], "time_limit");
    if (!(options.time_limit_s > 0 && options.time_limit_s <= 86400)) {
      in.fail(root["time_limit"], "time_limit",
              "expected seconds above 0 and at most 86400, found '" + root["time_limit"].Scalar() +
                  "'");
    }
  }
  if (root["repeat"]) options.repeat = int(in.whole_number(root["repeat"], "repeat", 1, 1000));
  return options;
}

}  // namespace gplan

#include "harness/motionbenchmaker.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/input_file.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& config_file, const std::string& path) {
  return fs::absolute(fs::path(config_file).parent_path() / path).lexically_normal().string();
}

}  // namespace

const std::vector<std::string>& motionbenchmaker_keys() {
  static const std::vector<std::string> keys = {"problems", "robot", "scenarios", "first"};
  return keys;
}

MotionBenchMakerSet read_motionbenchmaker(const gplanner::YamlReader& in, const YAML::Node& node,
                                          const std::string& config_file) {
  const std::string key = "motionbenchmaker";
  in.expect_map(node, key, {"problems", "robot", "scenarios", "first"});
  MotionBenchMakerSet set;
  const YAML::Node problems = in.required(node, key, "problems");
  set.folder = absolute(config_file, in.text(problems, key + ".problems"));
  std::error_code error;
  if (!fs::is_directory(set.folder, error)) {
    in.fail(problems, key + ".problems",
            "'" + set.folder + "' is not a folder; name the folder of the scenarios");
  }
  const YAML::Node robot = in.required(node, key, "robot");
  in.expect_map(robot, key + ".robot", {"urdf", "srdf", "packages"});
  set.urdf = absolute(config_file,
                      in.text(in.required(robot, key + ".robot", "urdf"), key + ".robot.urdf"));
  gplanner::check_input_file(set.urdf, gplanner::kUrdfFile,
                             in.at(robot["urdf"], key + ".robot.urdf"));
  if (robot["srdf"]) {
    set.srdf = absolute(config_file, in.text(robot["srdf"], key + ".robot.srdf"));
    gplanner::check_input_file(set.srdf, gplanner::kSrdfFile,
                               in.at(robot["srdf"], key + ".robot.srdf"));
  }
  if (robot["packages"]) {
    const YAML::Node map = robot["packages"];
    if (!map.IsMap())
      in.fail(map, key + ".robot.packages", "expected a map of package name: folder");
    for (const auto& entry : map) {
      const std::string name = entry.first.as<std::string>();
      set.packages[name] =
          absolute(config_file, in.text(entry.second, key + ".robot.packages." + name));
    }
  }
  std::vector<std::string> scenarios;
  if (node["scenarios"]) {
    const YAML::Node list = node["scenarios"];
    if (!list.IsSequence() || list.size() == 0)
      in.fail(list, key + ".scenarios", "expected a list of scenario folder names");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = key + ".scenarios[" + std::to_string(i) + "]";
      const std::string name = in.text(list[i], where);
      if (!fs::is_directory(fs::path(set.folder) / name, error) ||
          name.find('/') != std::string::npos) {
        in.fail(list[i], where, "'" + name + "' is not a folder of " + set.folder);
      }
      scenarios.push_back(name);
    }
  } else {
    for (const auto& entry : fs::directory_iterator(set.folder, error))
      if (entry.is_directory()) scenarios.push_back(entry.path().filename().string());
    std::sort(scenarios.begin(), scenarios.end());
  }
  const std::size_t first =
      node["first"] ? in.whole_number(node["first"], key + ".first", 1, 1000000) : ~std::size_t(0);
  static const std::regex kScene("scene([0-9]+)\\.yaml");
  for (const std::string& scenario : scenarios) {
    std::vector<std::string> numbers;
    for (const auto& entry : fs::directory_iterator(fs::path(set.folder) / scenario, error)) {
      std::smatch m;
      const std::string name = entry.path().filename().string();
      if (std::regex_match(name, m, kScene)) numbers.push_back(m[1]);
    }
    std::sort(numbers.begin(), numbers.end());
    if (numbers.empty()) {
      in.fail(
          node["problems"], key + ".problems",
          "scenario '" + scenario + "' holds no sceneNNNN.yaml; name a MotionBenchMaker folder");
    }
    if (numbers.size() > first) numbers.resize(first);
    for (const std::string& number : numbers) {
      const fs::path dir = fs::path(set.folder) / scenario;
      MotionBenchMakerSet::Problem p{scenario, number,
                                     (dir / ("scene" + number + ".yaml")).string(),
                                     (dir / ("request" + number + ".yaml")).string()};
      if (!fs::is_regular_file(p.request, error)) {
        throw gplanner::InputError({p.scene, 0, "request"}, "has no request" + number +
                                                                ".yaml beside it; add it, or "
                                                                "remove the scene");
      }
      set.problems.push_back(std::move(p));
    }
  }
  return set;
}

std::vector<std::string> write_problem_scenes(const MotionBenchMakerSet& set,
                                              const std::string& folder) {
  using gplanner::yaml_scalar;
  std::vector<std::string> files;
  for (const MotionBenchMakerSet::Problem& p : set.problems) {
    const std::string file = (fs::path(folder) / (p.scenario + "." + p.number + ".yaml")).string();
    std::ofstream out(file);
    out << "# MotionBenchMaker problem " << p.number << " of " << p.scenario
        << ", written by gplan-bench\n"
        << "name: " << yaml_scalar(p.scenario + "." + p.number) << "\n"
        << "robot:\n  urdf: " << yaml_scalar(set.urdf) << "\n";
    if (!set.srdf.empty()) out << "  srdf: " << yaml_scalar(set.srdf) << "\n";
    if (!set.packages.empty()) {
      out << "  packages:\n";
      for (const auto& [name, path] : set.packages)
        out << "    " << yaml_scalar(name) << ": " << yaml_scalar(path) << "\n";
    }
    out << "moveit:\n  scene: " << yaml_scalar(p.scene) << "\n  request: " << yaml_scalar(p.request)
        << "\n";
    if (!out) throw std::runtime_error("cannot write " + file);
    files.push_back(file);
  }
  return files;
}

}  // namespace gplan

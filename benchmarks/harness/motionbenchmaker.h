#pragma once
// MotionBenchMaker problem sets in a gplan-bench configuration (key `motionbenchmaker:`):
// a folder of scenarios, each a folder of MoveIt planning scenes and motion plan
// requests (sceneNNNN.yaml, requestNNNN.yaml), planned with one robot. Each problem
// becomes a gplanner scene file that names its robot and its two MoveIt files
// (docs/scenes.md, "MoveIt files"); its records carry the scenario as their scene and
// the problem's index as their run.

#include <map>
#include <string>
#include <vector>

#include "gplanner/planner/scene/yaml_reader.h"

namespace gplan {

struct MotionBenchMakerSet {
  std::string folder;  // of the scenarios
  std::string urdf, srdf;
  std::map<std::string, std::string> packages;
  struct Problem {
    std::string scenario;  // its folder's name (box_panda)
    std::string number;    // NNNN of sceneNNNN.yaml
    std::string scene, request;
  };
  std::vector<Problem> problems;  // scenario by scenario, in file name order
};

// Reads the `motionbenchmaker:` map: problems (the folder), robot {urdf, srdf,
// packages}, and optionally scenarios (their folder names; default all) and first (the
// first N problems of each). Paths are relative to the configuration. Throws
// gplanner::InputError naming the configuration's line and key (or the folder) where a
// scenario holds no problem or a scene lacks its request.
MotionBenchMakerSet read_motionbenchmaker(const gplanner::YamlReader& in, const YAML::Node& node,
                                          const std::string& config_file);

// The keys `motionbenchmaker:` takes.
const std::vector<std::string>& motionbenchmaker_keys();

// Writes one gplanner scene file per problem into `folder` (named SCENARIO.NNNN.yaml)
// and returns their paths, in the set's order.
std::vector<std::string> write_problem_scenes(const MotionBenchMakerSet& set,
                                              const std::string& folder);

}  // namespace gplan

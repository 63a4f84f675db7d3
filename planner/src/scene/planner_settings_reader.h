#pragma once
// Reading a scene's `planner:` section over the built-in defaults (the one place where
// settings are known by their keys).

#include <yaml-cpp/yaml.h>

#include "gplanner/planner/scene/planner_settings.h"
#include "gplanner/planner/scene/yaml_reader.h"

namespace gplanner {

// The defaults with `overrides` (the scene's `planner:` map, or an undefined node)
// applied, every value checked against its range: an unknown key, a value that is not a
// number or one out of its range is an InputError naming the scene file, its line and
// `planner.KEY`.
PlannerSettings read_planner_settings(const YamlReader& in, const YAML::Node& overrides);

}  // namespace gplanner

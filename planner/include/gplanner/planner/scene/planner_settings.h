#pragma once
// Planner settings: the defaults of config/planner.yaml (built into the library) with a
// scene's overrides. Keys of nested maps are flattened with dots
// ("distance_weights.position").

#include <map>
#include <string>

namespace gplanner {

struct PlannerSettings {
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> words;

  // The value of a key the defaults define; throws std::out_of_range otherwise.
  double number(const std::string& key) const { return numbers.at(key); }
  const std::string& word(const std::string& key) const { return words.at(key); }
};

// The text of config/planner.yaml as built into the library.
const char* default_planner_settings_yaml();

}  // namespace gplanner

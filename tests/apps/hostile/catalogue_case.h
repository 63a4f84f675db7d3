#pragma once
// One case of the hostile-input catalogue (tests/apps/hostile/catalogue.yaml): the
// files it creates in a scratch folder, the gplan command line, and what the run must
// do. See catalogue.yaml's header for the format.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace gplanner::hostile {

struct CatalogueCase {
  std::string name;                   // the gtest parameter name
  std::string kind;                   // the class of issue 19 it belongs to
  YAML::Node files;                   // file name -> how to create it (see catalogue.yaml)
  std::vector<YAML::Node> arguments;  // gplan's arguments (text, or a map to build one)
  std::vector<int> exit_codes;        // any of these
  std::vector<std::string> message;   // fragments every one of which the message holds
  std::vector<std::string> absent;    // fragments the message must not hold (misleading)
  bool advice = true;                 // the message says what to change
  std::vector<std::string> outputs;   // files the run may create (exit 0 or 4 only)
  std::vector<std::string> changes;   // files the run may change (outputs written through)
  double limit_s = 20;                // killed as a hang after this long
  double max_s = 0;                   // > 0: the run must end within this (time limits)
  bool needs_non_root = false;        // permission cases: run as an unprivileged user
  YAML::Node output_lacks;            // file (or stdout, stderr) -> fragments it must not hold
  std::vector<std::string> output_yaml;  // outputs that must read back as YAML
};

// The cases of a catalogue file; throws std::runtime_error naming the entry at fault.
std::vector<CatalogueCase> load_catalogue(const std::string& file);

// The bytes a text specification stands for: a scalar is itself; a map is
// prefix + text x repeat + suffix, or the concatenation of its `parts` (each such a
// specification). "$DIR" is replaced by `folder`.
std::string build_text(const YAML::Node& spec, const std::string& folder);

}  // namespace gplanner::hostile

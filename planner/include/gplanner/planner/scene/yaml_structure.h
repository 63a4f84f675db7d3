#pragma once
// The structure of a YAML file, checked through yaml-cpp's event API before a node tree
// is built: for the scene loader and gplan-bench's configurations (not installed).

#include <cstdint>
#include <yaml-cpp/yaml.h>

#include <string>

#include "gplanner/planner/scene/input_file.h"

namespace gplanner {

// The most nodes a document may expand to through its aliases.
inline constexpr std::uint64_t kMaxExpandedYamlNodes = 1000000;

// Throws InputError naming `path`, the line and the key path unless `text` is one YAML
// document that parses, with no key given twice in a map, no anchor or alias within the
// top-level map's `settings_key` (the planner settings), and aliases that expand the
// document to at most kMaxExpandedYamlNodes nodes. Parser errors are explained: a tab
// indenting a line, nesting beyond yaml-cpp's depth guard, and the others as "malformed
// YAML" with what yaml-cpp says.
void check_yaml_structure(const std::string& text, const std::string& path,
                          const std::string& settings_key);

// The YAML document in the file at `path`: read through read_input_file (a regular file
// of `kind`), checked by check_yaml_structure, then parsed; every problem an InputError
// naming the file (and the line where yaml-cpp says it).
YAML::Node load_checked_yaml(const std::string& path, const InputFileKind& kind,
                             const std::string& settings_key);

}  // namespace gplanner

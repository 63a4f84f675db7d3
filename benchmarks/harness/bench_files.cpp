#include "harness/bench_files.h"

#include <filesystem>
#include <iostream>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/scene/input_file.h"

namespace gplan {

namespace fs = std::filesystem;

void write_text(const std::string& path, const std::string& text) {
  gplanner::write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

void write_config_copy(const std::string& dir, const std::string& config_file) {
  write_text((fs::path(dir) / "config.yaml").string(),
             gplanner::read_input_file(config_file, {"bench configuration", gplanner::kMiB},
                                       {config_file, 0, ""}));
}

void write_study_outputs(const std::string& dir, const std::string& config_file,
                         const std::string& csv, const std::string& table,
                         const std::string& partial_csv) {
  write_text((fs::path(dir) / "results.csv").string(), csv);
  write_text((fs::path(dir) / "results.md").string(), table);
  write_config_copy(dir, config_file);
  fs::remove(partial_csv);
  std::cout << table << std::flush;
  std::cerr << "results: " << dir << "\n";
}

}  // namespace gplan

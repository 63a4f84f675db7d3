#pragma once
// The files every `gplan-bench` run writes into its output folder, written atomically:
// a text file, the configuration as it was run, and a study's results.

#include <string>

namespace gplan {

// Writes `text` to `path` atomically (a reader never sees half a file).
void write_text(const std::string& path, const std::string& text);

// DIR/config.yaml: the configuration file as it was run.
void write_config_copy(const std::string& dir, const std::string& config_file);

// A study's outputs (the error-time and broad-phase kinds): DIR/results.csv (`csv`),
// DIR/results.md (`table`) and DIR/config.yaml; then removes the partial CSV written
// while the study ran, prints the table on standard output and says where the results
// are on standard error.
void write_study_outputs(const std::string& dir, const std::string& config_file,
                         const std::string& csv, const std::string& table,
                         const std::string& partial_csv);

}  // namespace gplan

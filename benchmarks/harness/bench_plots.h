#pragma once
// The plots of `gplan-bench` (plan-time distributions per scene and planner, the query
// tables' batch times, the error-against-time study's curves), drawn by
// benchmarks/harness/plot_bench.py, plot_error_time.py and plot_broad_phase.py with matplotlib. The scripts
// are embedded in the binary (apps/CMakeLists.txt generates them as sources), so that an installed
// gplan needs no file from the source tree; each runs as `PYTHON - CSV OUT_DIR` with the script on
// its standard input, no shell in between.
//
// PYTHON: $GPLANNER_PYTHON where set (and then only it), else python3 from PATH, else
// /usr/bin/python3: the first that can import matplotlib.

#include <string>

namespace gplan {

// Draws the plots of `csv` (a CSV written by write_bench_csv_*) into `out_dir` (created
// when missing) with matplotlib; returns true when drawn. When no python3 with matplotlib
// is found, returns false and sets `notice` to one line saying what to install
// (apt-get install python3-matplotlib). When the script fails (a bad CSV: exit 2; an
// output that cannot be written: exit 1), its message goes to stderr as it wrote it, and
// `notice` says that the plots were not drawn and the script's exit code.
bool draw_bench_plots(const std::string& csv, const std::string& out_dir, std::string* notice);

// The same for the error-against-time study's CSV (benchmarks/harness/error_time_record.h), with
// benchmarks/harness/plot_error_time.py: per scene, error against time, one curve per knob.
bool draw_error_time_plots(const std::string& csv, const std::string& out_dir, std::string* notice);

// The same for the broad-phase study's CSV (benchmarks/harness/broad_phase_record.h), with
// benchmarks/harness/plot_broad_phase.py: median frame time against the sphere count, a curve per
// method.
bool draw_broad_phase_plots(const std::string& csv, const std::string& out_dir,
                            std::string* notice);

}  // namespace gplan

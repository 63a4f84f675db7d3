#include "harness/error_time_record.h"

#include <cstdio>
#include <ostream>
#include <sstream>

namespace gplan {
namespace {

std::string count_text(long long value) { return value < 0 ? "" : std::to_string(value); }

std::string time_text(double seconds) {
  char text[32];
  if (seconds >= 1) {
    std::snprintf(text, sizeof text, "%.2f s", seconds);
  } else if (seconds >= 1e-3) {
    std::snprintf(text, sizeof text, "%.2f ms", seconds * 1e3);
  } else {
    std::snprintf(text, sizeof text, "%.1f us", seconds * 1e6);
  }
  return text;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// Markdown: a '|' in a cell would split it.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

void write_error_time_csv_header(std::ostream& out) {
  out << "scene,knob,value,checker,time_s,missed,extra,undecided,total,runs,solved,path_fails,"
         "path_undecided\n";
}

void write_error_time_csv_line(std::ostream& out, const ErrorTimePoint& p) {
  char time[32];
  std::snprintf(time, sizeof time, "%.9g", p.time_s);
  out << csv_field(p.scene) << ',' << csv_field(p.knob) << ',' << csv_field(p.value) << ','
      << csv_field(p.checker) << ',' << time << ',' << count_text(p.missed) << ','
      << count_text(p.extra) << ',' << count_text(p.undecided) << ',' << p.total << ','
      << count_text(p.runs) << ',' << count_text(p.solved) << ',' << count_text(p.path_fails) << ','
      << count_text(p.path_undecided) << '\n';
}

void write_error_time_table(std::ostream& out, const std::string& experiment,
                            const std::vector<ErrorTimePoint>& points,
                            const std::vector<std::string>& notices) {
  out << "# Error against time: " << cell(experiment) << "\n";
  std::string scene;
  bool first = true;
  for (const ErrorTimePoint& p : points) {
    if (first || p.scene != scene) {
      scene = p.scene;
      first = false;
      out << "\n## " << cell(scene) << "\n\n"
          << "| knob | value | checker | time | missed | extra | undecided | of | solved | "
             "paths failing the truth | paths undecided |\n"
          << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    }
    out << "| " << cell(p.knob) << " | " << cell(p.value) << " | " << cell(p.checker) << " | "
        << time_text(p.time_s) << " | " << count_text(p.missed) << " | " << count_text(p.extra)
        << " | " << count_text(p.undecided) << " | " << p.total << " | " << count_text(p.solved)
        << " | " << count_text(p.path_fails) << " | " << count_text(p.path_undecided) << " |\n";
  }
  if (!notices.empty()) {
    out << "\nLeft out:\n\n";
    for (const std::string& notice : notices) out << "- " << notice << "\n";
  }
}

std::string error_time_progress_line(const ErrorTimePoint& p) {
  std::ostringstream line;
  line << p.scene << " " << p.knob << " " << p.value << " " << p.checker << ": "
       << time_text(p.time_s);
  if (p.planning()) {
    line << " median plan time, " << p.solved << "/" << p.runs << " solved, " << p.path_fails
         << " paths failing the truth";
    if (p.path_undecided > 0) line << " (" << p.path_undecided << " undecided)";
  } else {
    line << ", " << p.missed << " missed, " << p.extra << " extra of " << p.total;
    if (p.undecided > 0) line << " (" << p.undecided << " undecided)";
  }
  return line.str();
}

}  // namespace gplan

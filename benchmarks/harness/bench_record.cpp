#include "bench_record.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace gplan {
namespace {

std::string quoted(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number(double value) {
  if (!std::isfinite(value)) return "";
  std::ostringstream text;
  text << std::setprecision(9) << value;
  return text.str();
}

std::string count(long long value) { return value < 0 ? "" : std::to_string(value); }

// Splits one CSV record; `in` supplies continuation lines of quoted fields.
std::vector<std::string> split_csv(std::string line, std::istream& in, int* line_number) {
  std::vector<std::string> fields(1);
  bool in_quotes = false;
  for (std::size_t i = 0;; ++i) {
    if (i == line.size()) {
      if (!in_quotes) break;
      std::string next;
      if (!std::getline(in, next)) throw std::runtime_error("a quoted field is not closed");
      ++*line_number;
      line += "\n" + next;
    }
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

double parse_number(const std::string& field) {
  if (field.empty()) return kNotMeasured;
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (end == field.c_str() || *end != '\0') throw std::runtime_error("'" + field + "' is no number");
  return value;
}

long long parse_count(const std::string& field) {
  if (field.empty()) return -1;
  if (field.find_first_not_of("0123456789") != std::string::npos || field.size() > 18)
    throw std::runtime_error("'" + field + "' is no count");
  return std::stoll(field);
}

// Our planners' stage times and rounds (from issue 33), before note.
const std::vector<std::string>& stage_columns() {
  static const std::vector<std::string> columns = {"sampling_s", "state_checks_s", "knn_s",
                                                   "search_s",   "edge_checks_s",  "rounds"};
  return columns;
}

// The CSV layouts gplan-bench has written: this version's; before device (until issue
// 36); before gpu_calls (issue 33's first figures); before the stage columns (issues 22
// to 32); before check_time_s too (until issue 22).
enum class CsvLayout { kCurrent, kBeforeDevice, kBeforeGpuCalls, kBeforeStages, kBeforeCheckTime };

// A layout's columns, made once per layout (records are read one by one).
const std::vector<std::string>& columns_of(CsvLayout layout) {
  static const std::vector<std::string> current = bench_csv_columns();
  static const std::vector<std::string> before_device = [] {
    std::vector<std::string> all = bench_csv_columns();
    all.erase(std::find(all.begin(), all.end(), "device"));
    return all;
  }();
  static const std::vector<std::string> before_gpu_calls = [] {
    std::vector<std::string> all = before_device;
    all.erase(std::find(all.begin(), all.end(), "gpu_calls"));
    return all;
  }();
  static const std::vector<std::string> before_stages = [] {
    std::vector<std::string> all = before_gpu_calls;
    for (const std::string& c : stage_columns()) all.erase(std::find(all.begin(), all.end(), c));
    return all;
  }();
  static const std::vector<std::string> before_check_time = [] {
    std::vector<std::string> all = before_stages;
    all.erase(std::find(all.begin(), all.end(), "check_time_s"));
    return all;
  }();
  switch (layout) {
    case CsvLayout::kCurrent:
      return current;
    case CsvLayout::kBeforeDevice:
      return before_device;
    case CsvLayout::kBeforeGpuCalls:
      return before_gpu_calls;
    case CsvLayout::kBeforeStages:
      return before_stages;
    case CsvLayout::kBeforeCheckTime:
      break;
  }
  return before_check_time;
}

// One record from its fields, as many as the layout's columns.
BenchRecord record_from_fields(const std::vector<std::string>& f,
                               CsvLayout layout = CsvLayout::kCurrent) {
  const std::vector<std::string>& columns = columns_of(layout);
  if (f.size() != columns.size()) {
    throw std::runtime_error(std::to_string(f.size()) + " fields, not " +
                             std::to_string(columns.size()));
  }
  std::size_t column = 0;
  try {
    BenchRecord r;
    r.experiment = f[column++];
    r.scene = f[column++];
    r.planner = f[column++];
    r.checker = f[column++];
    r.run = static_cast<int>(parse_count(f[column++]));
    r.seed = static_cast<std::uint64_t>(parse_count(f[column++]));
    r.status = f[column++];
    const std::string solved = f[column++];
    if (solved != "0" && solved != "1") throw std::runtime_error("'" + solved + "' is not 0 or 1");
    r.solved = solved == "1";
    r.time_s = parse_number(f[column++]);
    r.simplify_time_s = parse_number(f[column++]);
    r.length = parse_number(f[column++]);
    r.simplified_length = parse_number(f[column++]);
    r.checks = parse_count(f[column++]);
    if (layout != CsvLayout::kBeforeCheckTime) r.check_time_s = parse_number(f[column++]);
    r.graph_states = parse_count(f[column++]);
    r.memory_mb = parse_number(f[column++]);
    r.path_check = f[column++];
    r.work = parse_count(f[column++]);
    r.collisions = parse_count(f[column++]);
    if (layout == CsvLayout::kCurrent || layout == CsvLayout::kBeforeDevice ||
        layout == CsvLayout::kBeforeGpuCalls) {
      r.sampling_s = parse_number(f[column++]);
      r.state_checks_s = parse_number(f[column++]);
      r.knn_s = parse_number(f[column++]);
      r.search_s = parse_number(f[column++]);
      r.edge_checks_s = parse_number(f[column++]);
      r.rounds = parse_count(f[column++]);
    }
    if (layout == CsvLayout::kCurrent || layout == CsvLayout::kBeforeDevice)
      r.gpu_calls = parse_count(f[column++]);
    if (layout == CsvLayout::kCurrent) r.device = parse_count(f[column++]);
    r.note = f[column++];
    return r;
  } catch (const std::exception& e) {
    throw std::runtime_error("column " + columns[column - 1] + ": " + e.what());
  }
}

}  // namespace

const std::vector<std::string>& bench_csv_columns() {
  static const std::vector<std::string> columns = {"experiment",
                                                   "scene",
                                                   "planner",
                                                   "checker",
                                                   "run",
                                                   "seed",
                                                   "status",
                                                   "solved",
                                                   "time_s",
                                                   "simplify_time_s",
                                                   "length",
                                                   "simplified_length",
                                                   "checks",
                                                   "check_time_s",
                                                   "graph_states",
                                                   "memory_mb",
                                                   "path_check",
                                                   "work",
                                                   "collisions",
                                                   "sampling_s",
                                                   "state_checks_s",
                                                   "knn_s",
                                                   "search_s",
                                                   "edge_checks_s",
                                                   "rounds",
                                                   "gpu_calls",
                                                   "device",
                                                   "note"};
  return columns;
}

void write_bench_csv_header(std::ostream& out) {
  const auto& columns = bench_csv_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
}

void write_bench_csv_line(std::ostream& out, const BenchRecord& r) {
  out << quoted(r.experiment) << ',' << quoted(r.scene) << ',' << quoted(r.planner) << ','
      << quoted(r.checker) << ',' << r.run << ',' << r.seed << ',' << quoted(r.status) << ','
      << (r.solved ? 1 : 0) << ',' << number(r.time_s) << ',' << number(r.simplify_time_s) << ','
      << number(r.length) << ',' << number(r.simplified_length) << ',' << count(r.checks) << ','
      << number(r.check_time_s) << ',' << count(r.graph_states) << ',' << number(r.memory_mb) << ','
      << quoted(r.path_check) << ',' << count(r.work) << ',' << count(r.collisions) << ','
      << number(r.sampling_s) << ',' << number(r.state_checks_s) << ',' << number(r.knn_s) << ','
      << number(r.search_s) << ',' << number(r.edge_checks_s) << ',' << count(r.rounds) << ','
      << count(r.gpu_calls) << ',' << count(r.device) << ',' << quoted(r.note) << "\n";
}

BenchRecord parse_bench_csv_record(const std::string& text) {
  std::istringstream rest;
  int line_number = 0;
  std::string line = text;
  while (!line.empty() && line.back() == '\n') line.pop_back();
  return record_from_fields(split_csv(line, rest, &line_number));
}

std::vector<BenchRecord> read_bench_csv(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot be read");
  std::vector<BenchRecord> records;
  CsvLayout layout = CsvLayout::kCurrent;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const int first_line = line_number;
    std::vector<std::string> f;
    try {
      f = split_csv(line, in, &line_number);
    } catch (const std::exception& e) {
      throw std::runtime_error(file + ":" + std::to_string(first_line) + ": " + e.what());
    }
    if (first_line == 1) {
      bool known = false;
      for (const CsvLayout candidate :
           {CsvLayout::kCurrent, CsvLayout::kBeforeDevice, CsvLayout::kBeforeGpuCalls,
            CsvLayout::kBeforeStages, CsvLayout::kBeforeCheckTime}) {
        if (f == columns_of(candidate)) {
          layout = candidate;
          known = true;
        }
      }
      if (!known) throw std::runtime_error(file + ":1: not a gplan-bench CSV (the header differs)");
      continue;
    }
    if (f.size() == 1 && f[0].empty()) continue;
    try {
      records.push_back(record_from_fields(f, layout));
    } catch (const std::exception& e) {
      throw std::runtime_error(file + ":" + std::to_string(first_line) + ": " + e.what());
    }
  }
  return records;
}

}  // namespace gplan

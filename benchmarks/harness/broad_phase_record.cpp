#include "harness/broad_phase_record.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <ostream>
#include <set>

namespace gplan {
namespace {

// The seed's Table I (GeForce G105M, CUDA 5.5, rendering included): average FPS.
struct SeedRow {
  std::uint64_t count;
  double sequential_fps, parallel_fps, speedup;
};
constexpr SeedRow kSeedTable[] = {{64, 59.31, 36.49, 0.62},
                                  {128, 19.43, 18.39, 0.95},
                                  {192, 9.35, 9.73, 1.04},
                                  {256, 5.36, 6.20, 1.16},
                                  {320, 3.42, 4.34, 1.27}};

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// Three significant digits, no exponent below 1e9.
std::string figure(double value) {
  char text[64];
  if (value >= 100 || value == 0) {
    std::snprintf(text, sizeof text, "%.0f", value);
  } else {
    std::snprintf(text, sizeof text, "%.3g", value);
  }
  return text;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

const BroadPhasePoint* find(const std::vector<BroadPhasePoint>& points, std::uint64_t count,
                            const std::string& method) {
  for (const BroadPhasePoint& p : points)
    if (p.count == count && p.method == method) return &p;
  return nullptr;
}

}  // namespace

void write_broad_phase_csv_header(std::ostream& out) {
  out << "count,method,frames,pairs_mean,mean_ms,median_ms,min_ms,max_ms,fps_mean,speedup,"
         "reruns,mismatches,note\n";
}

void write_broad_phase_csv_line(std::ostream& out, const BroadPhasePoint& p) {
  out << p.count << "," << p.method << "," << p.frames << ",";
  if (p.ran()) {
    char text[512];
    std::snprintf(text, sizeof text, "%.3f,%.6g,%.6g,%.6g,%.6g,%.6g,", p.pairs_mean, p.mean_ms,
                  p.median_ms, p.min_ms, p.max_ms, p.fps_mean);
    out << text;
    if (p.speedup >= 0) {
      std::snprintf(text, sizeof text, "%.6g", p.speedup);
      out << text;
    }
  } else {
    out << ",,,,,,";
  }
  out << "," << p.reruns << "," << p.mismatches << "," << csv_field(p.note) << "\n";
}

std::vector<std::string> broad_phase_crossovers(const std::vector<BroadPhasePoint>& points) {
  std::set<std::uint64_t> counts;
  for (const BroadPhasePoint& p : points)
    if (p.ran()) counts.insert(p.count);
  std::vector<std::string> lines;
  std::string current;
  std::uint64_t first = 0, last = 0;
  const auto close = [&] {
    if (current.empty()) return;
    lines.push_back(current + ": " +
                    (first == last ? std::to_string(first)
                                   : std::to_string(first) + " to " + std::to_string(last)) +
                    " spheres");
  };
  for (const std::uint64_t n : counts) {
    const BroadPhasePoint* best = nullptr;
    for (const BroadPhasePoint& p : points)
      if (p.count == n && p.ran() && (!best || p.median_ms < best->median_ms)) best = &p;
    if (best->method != current) {
      close();
      current = best->method;
      first = n;
    }
    last = n;
  }
  close();
  return lines;
}

void write_broad_phase_table(std::ostream& out, const std::string& experiment,
                             const std::vector<BroadPhasePoint>& points,
                             const std::vector<std::string>& notices) {
  std::vector<std::string> methods;
  std::set<std::uint64_t> counts;
  for (const BroadPhasePoint& p : points) {
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end())
      methods.push_back(p.method);
    counts.insert(p.count);
  }
  out << "# gplan bench " << experiment << " (broad-phase)\n\n";
  out << "Frame time: the broad phase of one frame, spheres in and pairs out (host to device "
         "and back included for the GPU methods); FPS: the mean of the frames' 1 / time, as "
         "the seed averages its FPS readings.\n\n";

  out << "## The seed's Table I beside ours\n\n"
         "| spheres | seed: sequential FPS | seed: parallel FPS | seed: speed-up | "
         "cpu-all-pairs FPS | gpu-all-pairs FPS | speed-up |\n"
         "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const SeedRow& row : kSeedTable) {
    const BroadPhasePoint* cpu = find(points, row.count, "cpu-all-pairs");
    const BroadPhasePoint* gpu = find(points, row.count, "gpu-all-pairs");
    out << "| " << row.count << " | " << fixed(row.sequential_fps, 2) << " | "
        << fixed(row.parallel_fps, 2) << " | " << fixed(row.speedup, 2) << " | "
        << (cpu && cpu->ran() ? figure(cpu->fps_mean) : "-") << " | "
        << (gpu && gpu->ran() ? figure(gpu->fps_mean) : "-") << " | "
        << (cpu && cpu->ran() && gpu && gpu->ran() ? fixed(gpu->fps_mean / cpu->fps_mean, 2) : "-")
        << " |\n";
  }

  out << "\n## Median frame time (ms) per method\n\n| spheres | pairs |";
  for (const std::string& m : methods) out << " " << m << " |";
  out << " fastest |\n| ---: | ---: |";
  for (std::size_t i = 0; i < methods.size(); ++i) out << " ---: |";
  out << " --- |\n";
  std::map<std::string, std::string> not_run;  // method -> why, for the notes
  for (const std::uint64_t n : counts) {
    double pairs = -1;
    const BroadPhasePoint* best = nullptr;
    for (const BroadPhasePoint& p : points) {
      if (p.count != n || !p.ran()) continue;
      if (pairs < 0) pairs = p.pairs_mean;
      if (!best || p.median_ms < best->median_ms) best = &p;
    }
    out << "| " << n << " | " << (pairs < 0 ? "-" : figure(pairs)) << " |";
    for (const std::string& m : methods) {
      const BroadPhasePoint* p = find(points, n, m);
      if (p && p->ran()) {
        out << " " << figure(p->median_ms) << (p->mismatches ? " (MISMATCH)" : "") << " |";
      } else {
        out << " - |";
        if (p && !p->note.empty() && !not_run.count(m)) not_run[m] = p->note;
      }
    }
    out << " " << (best ? best->method : "-") << " |\n";
  }
  for (const auto& [method, why] : not_run) out << "\n- " << method << " `-`: " << why;
  if (!not_run.empty()) out << "\n";

  out << "\n## Speed-up over cpu-all-pairs (FPS ratio)\n\n| spheres |";
  for (const std::string& m : methods) out << " " << m << " |";
  out << "\n| ---: |";
  for (std::size_t i = 0; i < methods.size(); ++i) out << " ---: |";
  out << "\n";
  for (const std::uint64_t n : counts) {
    out << "| " << n << " |";
    for (const std::string& m : methods) {
      const BroadPhasePoint* p = find(points, n, m);
      out << " " << (p && p->ran() && p->speedup >= 0 ? figure(p->speedup) : "-") << " |";
    }
    out << "\n";
  }

  out << "\n## Fastest method (crossovers)\n\n";
  for (const std::string& line : broad_phase_crossovers(points)) out << "- " << line << "\n";
  if (!notices.empty()) {
    out << "\n## Notices\n\n";
    for (const std::string& notice : notices) out << "- " << notice << "\n";
  }
}

std::string broad_phase_progress_line(const BroadPhasePoint& p) {
  if (!p.ran()) return p.method + ": not run (" + p.note + ")";
  std::string line = p.method + ": " + std::to_string(p.frames) + " frames, median " +
                     figure(p.median_ms) + " ms (" + figure(p.fps_mean) + " FPS), " +
                     figure(p.pairs_mean) + " pairs";
  if (p.speedup >= 0 && p.method != "cpu-all-pairs")
    line += ", " + figure(p.speedup) + "x cpu-all-pairs";
  if (p.reruns) line += ", " + std::to_string(p.reruns) + " re-runs";
  if (p.mismatches) line += ", " + std::to_string(p.mismatches) + " MISMATCHED frames";
  return line;
}

}  // namespace gplan

#include "bench_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <ostream>
#include <sstream>

#include "gplanner/planner/output/text_escaping.h"
#include "harness/query_runs.h"

namespace gplan {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The value at fraction p of the sorted values (linear between neighbours).
double quantile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return kNaN;
  const double at = p * double(sorted.size() - 1);
  const std::size_t low = static_cast<std::size_t>(std::floor(at));
  const std::size_t high = std::min(low + 1, sorted.size() - 1);
  return sorted[low] + (at - double(low)) * (sorted[high] - sorted[low]);
}

std::string seconds(double s) {
  if (!std::isfinite(s)) return "-";
  std::ostringstream text;
  if (s < 1) {
    text << std::fixed << std::setprecision(s < 0.01 ? 2 : 1) << s * 1000 << " ms";
  } else {
    text << std::fixed << std::setprecision(s < 10 ? 2 : 1) << s << " s";
  }
  return text.str();
}

// Rows of cells in columns two spaces apart, each as wide as its widest cell.
void print_aligned(std::ostream& out, const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> widths(rows[0].size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += row[c] + std::string(c + 1 < row.size() ? widths[c] - row[c].size() + 2 : 0, ' ');
    out << line << "\n";
  }
}

std::string range(double low, double high) {
  return std::isfinite(low) ? seconds(low) + " - " + seconds(high) : "-";
}

}  // namespace

double median_of(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return quantile(values, 0.5);
}

std::vector<GroupSummary> summarize(const std::vector<BenchRecord>& records) {
  std::vector<GroupSummary> groups;
  std::map<std::string, std::size_t> index;
  std::map<std::string, std::vector<const BenchRecord*>> members;
  for (const BenchRecord& r : records) {
    GroupSummary g;
    g.experiment = r.experiment;
    g.scene = r.scene;
    g.planner = r.planner;
    g.checker = r.checker;
    if (!index.count(g.key())) {
      index[g.key()] = groups.size();
      groups.push_back(g);
    }
    members[g.key()].push_back(&r);
  }
  for (GroupSummary& g : groups) {
    std::vector<double> times, lengths, check_shares;
    std::vector<std::pair<double, bool>> timed;  // time, found no path
    for (const BenchRecord* r : members[g.key()]) {
      if (r->status == "invalid") continue;  // a problem set's problem not run
      ++g.runs;
      if (r->status == "crash" || r->status == "error") ++g.crashes;
      if (!r->path_check.empty()) ++g.paths_checked;
      if (r->path_check == "fail") ++g.path_failures;
      if (r->solved) ++g.solved;
      if (std::isfinite(r->check_time_s) && r->time_s > 0)
        check_shares.push_back(r->check_time_s / r->time_s);
      if (std::isfinite(r->time_s)) {
        const bool failed = !r->solved && !is_query_table(r->planner);
        timed.push_back({r->time_s, failed});
        times.push_back(r->time_s);
      }
      const double length = std::isfinite(r->simplified_length) ? r->simplified_length : r->length;
      if (r->solved && std::isfinite(length)) lengths.push_back(length);
    }
    g.success_rate = is_query_table(g.planner)
                         ? (g.runs > g.crashes ? 1.0 : 0.0)
                         : (g.runs ? double(g.solved) / g.runs : 0.0);
    std::sort(times.begin(), times.end());
    std::sort(timed.begin(), timed.end());
    g.median_time_s = quantile(times, 0.5);
    g.q1_time_s = quantile(times, 0.25);
    g.q3_time_s = quantile(times, 0.75);
    g.min_time_s = times.empty() ? kNaN : times.front();
    g.max_time_s = times.empty() ? kNaN : times.back();
    if (!timed.empty()) {
      const std::size_t n = timed.size();
      g.median_is_lower_bound = timed[n / 2].second || (n % 2 == 0 && timed[n / 2 - 1].second);
    }
    g.median_length = median_of(lengths);
    g.median_check_share = median_of(check_shares);
  }
  // The FCL reference of each group.
  for (GroupSummary& g : groups) {
    g.speedup_over_fcl = kNaN;
    const GroupSummary* reference = nullptr;
    for (const GroupSummary& other : groups) {
      if (other.scene != g.scene || other.checker != "fcl" || !std::isfinite(other.median_time_s))
        continue;
      if (is_query_table(g.planner) != is_query_table(other.planner)) continue;
      if (is_query_table(g.planner) && other.planner != g.planner) continue;
      if (other.planner == g.planner) {
        reference = &other;
        break;
      }
      if (!reference || other.median_time_s < reference->median_time_s) reference = &other;
    }
    if (reference && reference != &g && g.median_time_s > 0) {
      g.reference = reference->planner + "@fcl";
      g.speedup_over_fcl = reference->median_time_s / g.median_time_s;
      g.reference_is_lower_bound = reference->median_is_lower_bound;
    }
  }
  return groups;
}

void print_summary(std::ostream& out, const std::vector<GroupSummary>& groups) {
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"scene", "planner@checker", "runs", "success", "median", "spread (q1-q3)",
                  "min-max", "path length", "in checks", "vs FCL", "re-check", "crashes"});
  for (const GroupSummary& g : groups) {
    std::ostringstream success, length, in_checks, speedup, recheck;
    const bool table = is_query_table(g.planner);
    success << (table ? "-" : std::to_string(g.solved) + "/" + std::to_string(g.runs));
    if (std::isfinite(g.median_length)) length << std::fixed << std::setprecision(2) << g.median_length;
    else length << "-";
    if (std::isfinite(g.median_check_share)) {
      in_checks << std::fixed << std::setprecision(0) << 100 * g.median_check_share << "%";
    } else {
      in_checks << "-";
    }
    if (std::isfinite(g.speedup_over_fcl)) {
      // A median that is a lower bound makes the ratio a bound: at least (">") when the
      // reference's is, at most ("<") when this group's is, unknown ("~") when both are.
      const char* bound = g.reference_is_lower_bound ? (g.median_is_lower_bound ? "~" : ">")
                                                     : (g.median_is_lower_bound ? "<" : "");
      speedup << std::setprecision(3) << bound << g.speedup_over_fcl
              << "x (" << g.reference << ")";
    } else {
      speedup << "-";
    }
    if (g.path_failures) {
      recheck << g.path_failures << " of " << g.paths_checked << " FAILED";
    } else {
      recheck << (g.paths_checked ? std::to_string(g.paths_checked) + " pass" : "-");
    }
    rows.push_back({g.scene, g.planner + "@" + g.checker, std::to_string(g.runs), success.str(),
                    (g.median_is_lower_bound ? ">" : "") + seconds(g.median_time_s),
                    range(g.q1_time_s, g.q3_time_s), range(g.min_time_s, g.max_time_s), length.str(),
                    in_checks.str(), speedup.str(), recheck.str(), std::to_string(g.crashes)});
  }
  std::vector<std::size_t> width(rows[0].size(), 0);
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::ostringstream line;
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      line << (c ? "  " : "") << std::left << std::setw(int(width[c])) << rows[r][c];
    }
    std::string text = line.str();
    text.erase(text.find_last_not_of(' ') + 1);
    out << text << "\n";
    if (r == 0) {
      std::size_t total = 0;
      for (std::size_t w : width) total += w + 2;
      out << std::string(total - 2, '-') << "\n";
    }
  }
}

void print_stage_summary(std::ostream& out, const std::vector<BenchRecord>& records) {
  struct Stages {
    int runs = 0;
    std::vector<double> total, sampling, states, knn, search, edges, shortcut, other, rounds,
        gpu_calls;
  };
  std::vector<std::string> order;
  std::map<std::string, Stages> groups;
  for (const BenchRecord& r : records) {
    if (!std::isfinite(r.sampling_s)) continue;
    const std::string key = r.scene + " " + r.planner + "@" + r.checker;
    if (!groups.count(key)) order.push_back(key);
    Stages& g = groups[key];
    ++g.runs;
    if (!r.solved) continue;
    const double shortcut = std::isfinite(r.simplify_time_s) ? r.simplify_time_s : 0;
    g.total.push_back(r.time_s);
    g.sampling.push_back(r.sampling_s);
    g.states.push_back(r.state_checks_s);
    g.knn.push_back(r.knn_s);
    g.search.push_back(r.search_s);
    g.edges.push_back(r.edge_checks_s);
    g.shortcut.push_back(shortcut);
    g.other.push_back(r.time_s - r.sampling_s - r.state_checks_s - r.knn_s - r.search_s -
                      r.edge_checks_s - shortcut);
    if (r.rounds >= 0) g.rounds.push_back(double(r.rounds));
    if (r.gpu_calls >= 0) g.gpu_calls.push_back(double(r.gpu_calls));
  }
  if (order.empty()) return;
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"scene", "planner@checker", "solved", "plan time", "sampling", "state checks",
                  "k-NN", "search", "edge checks", "shortcutting", "other", "rounds",
                  "GPU calls"});
  for (const std::string& key : order) {
    const Stages& g = groups.at(key);
    const std::size_t space = key.find(' ');
    std::ostringstream solved;
    solved << g.total.size() << "/" << g.runs;
    const auto count = [](const std::vector<double>& values) {
      const double m = median_of(values);
      std::ostringstream text;
      if (std::isfinite(m)) {
        text << m;
      } else {
        text << "-";
      }
      return text.str();
    };
    rows.push_back({key.substr(0, space), key.substr(space + 1), solved.str(),
                    seconds(median_of(g.total)), seconds(median_of(g.sampling)),
                    seconds(median_of(g.states)), seconds(median_of(g.knn)),
                    seconds(median_of(g.search)), seconds(median_of(g.edges)),
                    seconds(median_of(g.shortcut)), seconds(median_of(g.other)), count(g.rounds),
                    count(g.gpu_calls)});
  }
  out << "\nstages (our planners' solved runs: the median of each; other: the plan time beyond "
         "the stages):\n";
  print_aligned(out, rows);
}

void print_problem_set_summary(std::ostream& out, const std::vector<BenchRecord>& records) {
  struct Tally {
    int total = 0, invalid = 0, solved = 0;
    std::vector<std::pair<double, bool>> times;  // valid runs: time, found no path
  };
  std::vector<std::string> order;
  std::map<std::string, Tally> tallies;
  for (const BenchRecord& r : records) {
    const std::string key = r.scene + " " + r.planner + "@" + r.checker;
    if (!tallies.count(key)) order.push_back(key);
    Tally& t = tallies[key];
    ++t.total;
    if (r.status == "invalid") {
      ++t.invalid;
      continue;
    }
    if (r.solved) ++t.solved;
    if (std::isfinite(r.time_s)) t.times.push_back({r.time_s, !r.solved});
  }
  // A quantile of the valid runs' times (nearest rank), '>' where it is a run that found
  // no path (a lower bound).
  auto quantile_text = [](std::vector<std::pair<double, bool>> times, double q) {
    if (times.empty()) return std::string("-");
    std::sort(times.begin(), times.end());
    const std::size_t i = std::min(times.size() - 1,
                                   static_cast<std::size_t>(std::ceil(q * times.size())) - (q > 0));
    return (times[i].second ? "> " : "") + seconds(times[i].first);
  };
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"scenario", "planner@checker", "solved / valid / total", "success", "median",
                  "p95"});
  for (const std::string& key : order) {
    const Tally& t = tallies.at(key);
    const int valid = t.total - t.invalid;
    const std::size_t space = key.find(' ');
    std::ostringstream counts, success;
    counts << t.solved << " / " << valid << " / " << t.total;
    if (valid > 0) {
      success << std::fixed << std::setprecision(1) << 100.0 * t.solved / valid << " %";
    } else {
      success << "-";
    }
    rows.push_back({key.substr(0, space), key.substr(space + 1), counts.str(), success.str(),
                    quantile_text(t.times, 0.5), quantile_text(t.times, 0.95)});
  }
  out << "\nproblems (median and p95 over the valid problems' runs, a run without a path at its "
         "full time):\n";
  print_aligned(out, rows);
  std::size_t invalid = 0;
  for (const BenchRecord& r : records) invalid += r.status == "invalid";
  if (invalid == 0) return;
  out << "invalid (start or goal in collision, not run):\n";
  std::set<std::string> said;
  for (const BenchRecord& r : records)
    if (r.status == "invalid" && said.insert(r.note).second)
      out << "  " << gplanner::terminal_text(r.note) << "\n";
}

}  // namespace gplan

#include "harness/broad_phase_study.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "harness/bench_files.h"
#include "harness/bench_plots.h"
#include "harness/broad_phase_motion.h"
#include "harness/broad_phase_record.h"
#include "gplanner/collision_gpu/broad_phase.h"
#include "gplanner/collision_gpu/gpu_broad_phase.h"
#include "gplanner/planner/output/text_escaping.h"
#include "interruption.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using gplanner::BroadPhaseMethod;
using gplanner::SpherePair;

constexpr int kExitMismatch = 3;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void say(const std::string& line) {
  std::cerr << gplanner::terminal_text(line) << "\n" << std::flush;
}

// One method at one count while its frames run.
struct MethodRun {
  std::string name;
  BroadPhaseMethod method{};
  std::vector<double> times_ms;
  double pairs_sum = 0;
  long long reruns = 0;
  long long mismatches = 0;
  std::string error;  // the method failed: what it said
  std::vector<SpherePair> pairs;
};

// The pairs of one method in one frame (sorted, for the comparison, after the clock
// stopped); false when it failed (run.error says why).
bool run_frame(MethodRun& run, const gplanner::SphereArrays& spheres, gplanner::GpuBroadPhase* gpu,
               double* ms) {
  try {
    const auto start = Clock::now();
    if (run.method == BroadPhaseMethod::kCpuAllPairs) {
      gplanner::all_pairs_cpu(spheres, &run.pairs);
    } else if (run.method == BroadPhaseMethod::kCpuSortSweep) {
      gplanner::sort_sweep_cpu(spheres, &run.pairs);
    } else {
      gpu->find_pairs(run.method, spheres, &run.pairs);
    }
    *ms = 1e3 * seconds_since(start);
    if (gplanner::is_gpu_method(run.method)) run.reruns += gpu->last_stats().reruns;
    gplanner::sort_pairs(&run.pairs);
    return true;
  } catch (const std::exception& e) {
    run.error = e.what();
    return false;
  }
}

// What differs between two sorted pair sets, for the error line.
std::string difference(const std::vector<SpherePair>& mine, const std::vector<SpherePair>& theirs) {
  std::vector<SpherePair> only_mine, only_theirs;
  std::set_difference(mine.begin(), mine.end(), theirs.begin(), theirs.end(),
                      std::back_inserter(only_mine));
  std::set_difference(theirs.begin(), theirs.end(), mine.begin(), mine.end(),
                      std::back_inserter(only_theirs));
  std::ostringstream text;
  text << mine.size() << " pairs against " << theirs.size() << "; " << only_mine.size()
       << " only here, " << only_theirs.size() << " missing";
  const SpherePair* first = !only_mine.empty()     ? &only_mine[0]
                            : !only_theirs.empty() ? &only_theirs[0]
                                                   : nullptr;
  if (first) text << " (first: " << first->i << ", " << first->j << ")";
  return text.str();
}

BroadPhasePoint summarize(const MethodRun& run, std::uint64_t count) {
  BroadPhasePoint p;
  p.count = count;
  p.method = run.name;
  p.frames = int(run.times_ms.size());
  p.reruns = run.reruns;
  p.mismatches = run.mismatches;
  if (!run.error.empty()) p.note = "error: " + run.error;
  if (!p.frames) return p;
  std::vector<double> t = run.times_ms;
  std::sort(t.begin(), t.end());
  double sum = 0, fps = 0;
  for (const double ms : t) {
    sum += ms;
    fps += 1e3 / std::max(ms, 1e-9);
  }
  p.mean_ms = sum / t.size();
  p.median_ms = t.size() % 2 ? t[t.size() / 2] : (t[t.size() / 2 - 1] + t[t.size() / 2]) / 2;
  p.min_ms = t.front();
  p.max_ms = t.back();
  p.fps_mean = fps / t.size();
  p.pairs_mean = run.pairs_sum / t.size();
  return p;
}

}  // namespace

int run_broad_phase_study(const BenchConfig& config, const std::string& dir, bool plots,
                          const std::function<bool()>& should_stop) {
  const BroadPhaseOptions& options = config.broad_phase;
  std::vector<std::string> notices;
  const auto notice = [&](const std::string& line) {
    notices.push_back(line);
    say("notice: " + line);
  };

  // The GPU, where a gpu method is asked for and one can be used.
  std::unique_ptr<gplanner::GpuBroadPhase> gpu;
  std::vector<std::string> gpu_methods;
  for (const std::string& name : options.methods) {
    BroadPhaseMethod method{};
    gplanner::parse_broad_phase_method(name, &method);
    if (gplanner::is_gpu_method(method)) gpu_methods.push_back(name);
  }
  std::string no_gpu;
  if (!gpu_methods.empty()) {
    std::string reason;
    if (gplanner::gpu_broad_phase_available(&reason)) {
      gpu = std::make_unique<gplanner::GpuBroadPhase>();
      say("GPU: " + gpu->device_name());
    } else {
      no_gpu = "no GPU can be used here (" + reason + ")";
      std::string list;
      for (const std::string& m : gpu_methods) list += (list.empty() ? "" : ", ") + m;
      notice(list + " left out: " + no_gpu + "; run where there is a GPU");
    }
  }

  const std::string partial = (fs::path(dir) / "results.partial.csv").string();
  std::ofstream partial_csv(partial);
  write_broad_phase_csv_header(partial_csv);
  std::vector<BroadPhasePoint> points;
  bool failed = false;
  for (std::size_t c = 0; c < options.counts.size() && !should_stop(); ++c) {
    const std::uint64_t n = options.counts[c];
    BouncingSpheres scene(n, options, config.seed);
    std::vector<MethodRun> runs;  // those that run here, the reference first
    std::vector<BroadPhasePoint> left_out;
    for (const BroadPhaseMethod method : gplanner::broad_phase_methods()) {
      const std::string name = gplanner::broad_phase_method_name(method);
      if (std::find(options.methods.begin(), options.methods.end(), name) == options.methods.end())
        continue;
      BroadPhasePoint p;
      p.count = n;
      p.method = name;
      const auto cap = options.max_count.find(name);
      if (gplanner::is_gpu_method(method) && !gpu) {
        p.note = no_gpu;
      } else if (cap != options.max_count.end() && n > cap->second) {
        p.note = "above its max_count " + std::to_string(cap->second);
      } else {
        MethodRun run;
        run.name = name;
        run.method = method;
        runs.push_back(std::move(run));
        continue;
      }
      left_out.push_back(p);
    }
    say("[" + std::to_string(c + 1) + "/" + std::to_string(options.counts.size()) + "] " +
        std::to_string(n) + " spheres (box side " + std::to_string(scene.box_side()) +
        "): " + std::to_string(runs.size()) + " methods" +
        (runs.empty() ? "" : ", the reference " + runs[0].name));

    // One untimed warm-up frame, then frames until `frames`, or the budget once
    // min_frames are done.
    const auto start = Clock::now();
    for (int frame = -1; frame < options.frames && !runs.empty() && !should_stop(); ++frame) {
      if (frame >= options.min_frames && seconds_since(start) >= options.count_budget_s) break;
      if (frame >= 0) scene.step();
      const gplanner::SphereArrays spheres = scene.arrays();
      const std::vector<SpherePair>* reference = nullptr;
      for (MethodRun& run : runs) {
        if (!run.error.empty()) continue;
        double ms = 0;
        if (!run_frame(run, spheres, gpu.get(), &ms)) {
          say("ERROR: " + std::to_string(n) + " spheres, " + run.name + ": " + run.error);
          failed = true;
          continue;
        }
        if (!reference) {
          reference = &run.pairs;
        } else if (run.pairs != *reference) {
          if (run.mismatches == 0) {
            say("MISMATCH: " + std::to_string(n) + " spheres, frame " + std::to_string(frame) +
                ": " + run.name + " found " + difference(run.pairs, *reference) + " of " +
                runs[0].name);
          }
          ++run.mismatches;
          failed = true;
        }
        if (frame >= 0) {
          run.times_ms.push_back(ms);
          run.pairs_sum += double(run.pairs.size());
        }
      }
    }
    if (should_stop()) break;
    std::vector<BroadPhasePoint> here;
    for (const MethodRun& run : runs) here.push_back(summarize(run, n));
    double cpu_fps = -1;
    for (const BroadPhasePoint& p : here)
      if (p.method == "cpu-all-pairs" && p.ran()) cpu_fps = p.fps_mean;
    for (BroadPhasePoint& p : here) {
      if (cpu_fps > 0 && p.ran()) p.speedup = p.fps_mean / cpu_fps;
      if (p.note.empty())
        p.note = &p == &here[0] ? "the reference" : "checked against " + here[0].method;
    }
    here.insert(here.end(), left_out.begin(), left_out.end());
    for (const BroadPhasePoint& p : here) {
      say("  " + broad_phase_progress_line(p));
      write_broad_phase_csv_line(partial_csv, p);
      points.push_back(p);
    }
    partial_csv.flush();
  }
  partial_csv.close();
  if (should_stop()) return report_interruption({partial + " (the counts done)"}, {});

  std::ostringstream csv, table;
  write_broad_phase_csv_header(csv);
  for (const BroadPhasePoint& p : points) write_broad_phase_csv_line(csv, p);
  write_broad_phase_table(table, config.name, points, notices);
  write_study_outputs(dir, config.file, csv.str(), table.str(), partial);
  const std::string results = (fs::path(dir) / "results.csv").string();
  const bool any_ran =
      std::any_of(points.begin(), points.end(), [](const BroadPhasePoint& p) { return p.ran(); });
  if (plots && !any_ran) std::cerr << "notice: no plots: no method ran\n";
  if (plots && any_ran) {
    std::string why;
    const std::string plot_dir = (fs::path(dir) / "plots").string();
    if (draw_broad_phase_plots(results, plot_dir, &why)) {
      std::cerr << "plots: " << plot_dir << "\n";
    } else {
      std::cerr << "notice: no plots: " << gplanner::terminal_text(why) << "\n";
    }
  }
  if (failed) {
    say("FAILED: a method's pairs differed from the reference's, or a method failed (see "
        "MISMATCH and ERROR above, and the mismatches column of " +
        results + ")");
    return kExitMismatch;
  }
  return 0;
}

}  // namespace gplan

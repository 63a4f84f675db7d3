#pragma once
// One point of the broad-phase study (one method at one sphere count) and its outputs: a
// CSV line (results.csv), the seed's Table I beside ours, the table of every method and
// count, and the crossovers (which method is fastest where) in results.md.
//
// CSV columns: count, method, frames, pairs_mean, mean_ms, median_ms, min_ms, max_ms,
// fps_mean, speedup, reruns, mismatches, note. A method that did not run at a count has
// frames 0, empty figures and a note (its cap, or no GPU).

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace gplan {

struct BroadPhasePoint {
  std::uint64_t count = 0;  // spheres
  std::string method;       // cpu-all-pairs, cpu-sort-sweep, gpu-all-pairs, ...
  int frames = 0;           // timed frames (0: not run)
  double pairs_mean = 0;    // overlapping pairs per frame
  // Frame times: transfers to and from the GPU included (the GPU methods).
  double mean_ms = 0, median_ms = 0, min_ms = 0, max_ms = 0;
  double fps_mean = 0;       // the mean of the frames' 1 / time, as the seed averages FPS readings
  double speedup = -1;       // fps_mean over cpu-all-pairs' at this count (-1: it did not run)
  long long reruns = 0;      // GPU frames run again after the pair buffer overflowed
  long long mismatches = 0;  // frames whose pair set differs from the reference's
  std::string note;          // why it did not run; which method was the reference

  bool ran() const { return frames > 0; }
};

void write_broad_phase_csv_header(std::ostream& out);
void write_broad_phase_csv_line(std::ostream& out, const BroadPhasePoint& point);

// The fastest method (median frame time) at each count where one ran, as ranges of
// counts: "cpu-all-pairs: 64 to 192", ... Each line one range, in count order.
std::vector<std::string> broad_phase_crossovers(const std::vector<BroadPhasePoint>& points);

// results.md: the seed's Table I beside ours (cpu-all-pairs against gpu-all-pairs at the
// seed's counts, where both ran), every method's median frame time per count, the
// crossovers, and `notices` (methods left out and why).
void write_broad_phase_table(std::ostream& out, const std::string& experiment,
                             const std::vector<BroadPhasePoint>& points,
                             const std::vector<std::string>& notices);

// One line for the progress output: "gpu-grid: 200 frames, median 0.041 ms, 61.2 pairs".
std::string broad_phase_progress_line(const BroadPhasePoint& point);

}  // namespace gplan

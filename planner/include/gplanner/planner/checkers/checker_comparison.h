#pragma once
// Two checkers' verdicts on the same configurations, with every disagreement judged by
// FCL: its verdict, and its distance against the tolerance band delta.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gplanner/planner/checkers/fcl_checker.h"

namespace gplanner {

struct CheckerComparison {
  std::size_t configurations = 0;
  std::size_t disagreements = 0;
  // A checker said free where FCL finds a collision: a miss, never allowed.
  std::size_t missed_collisions = 0;
  // A checker said collision where FCL finds none: allowed only within the band.
  std::size_t extra_within_band = 0;           // FCL distance < delta
  std::size_t extra_outside_band = 0;          // FCL distance >= delta
  double largest_extra_distance = 0;           // metres, over extra collisions
  std::vector<std::size_t> outside_band_rows;  // the first few, for reports
};

// Compares verdicts a and b (shape [n]) of configurations (shape [n, width]);
// disagreements are re-checked by `fcl` (collision and distance).
CheckerComparison compare_verdicts(const float* configurations, std::size_t n, std::size_t width,
                                   const std::uint8_t* a, const std::uint8_t* b, FclChecker* fcl,
                                   double delta);

}  // namespace gplanner

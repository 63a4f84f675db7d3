#include "gplanner/planner/checkers/checker_comparison.h"

#include <algorithm>

namespace gplanner {

CheckerComparison compare_verdicts(const float* configurations, std::size_t n, std::size_t width,
                                   const std::uint8_t* a, const std::uint8_t* b, FclChecker* fcl,
                                   double delta) {
  CheckerComparison result;
  result.configurations = n;
  std::vector<std::size_t> rows;
  std::vector<float> disputed;
  for (std::size_t i = 0; i < n; ++i) {
    if ((a[i] != 0) == (b[i] != 0)) continue;
    rows.push_back(i);
    disputed.insert(disputed.end(), configurations + i * width, configurations + (i + 1) * width);
  }
  result.disagreements = rows.size();
  if (rows.empty()) return result;
  std::vector<std::uint8_t> truth(rows.size());
  std::vector<double> distance(rows.size());
  fcl->check(disputed.data(), rows.size(), truth.data());
  fcl->distance(disputed.data(), rows.size(), distance.data());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (truth[k]) {
      ++result.missed_collisions;  // one of the two said free
    } else if (distance[k] < delta) {
      ++result.extra_within_band;
      result.largest_extra_distance = std::max(result.largest_extra_distance, distance[k]);
    } else {
      ++result.extra_outside_band;
      result.largest_extra_distance = std::max(result.largest_extra_distance, distance[k]);
      if (result.outside_band_rows.size() < 10) result.outside_band_rows.push_back(rows[k]);
    }
  }
  return result;
}

}  // namespace gplanner

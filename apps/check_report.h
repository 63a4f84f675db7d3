#pragma once
// What `gplan check` reports: the scene, the batch checked and its verdicts' summary, the
// GPU's figures, a --compare's outcome; printed as text, and as one JSON line (--json).

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>

#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/planner/checkers/checker_comparison.h"

namespace gplan {

// The GPU's part of one checker's last call.
struct GpuCallReport {
  std::string device;
  std::string traversal;
  gplanner::GpuCheckStats stats;
};

struct CheckReport {
  // The scene.
  std::string scene_file, scene_name, robot_name, base;
  std::size_t links = 0, robot_triangles = 0, checked_pairs = 0;
  int dof = 0;
  std::size_t width = 0;
  std::size_t obstacles = 0, obstacle_triangles = 0, dropped_obstacle_triangles = 0;
  double load_s = 0;
  double delta = 0;  // the tolerance band, metres
  // The check.
  std::string backend;
  double straight_line_collision = -1;  // where start -> goal first collides (0-1), -1 free
  std::size_t n = 0;
  unsigned long long seed = 0;
  std::size_t collisions = 0;
  double seconds = 0;  // the median of `repeat` runs
  std::size_t repeat = 1;
  std::optional<GpuCallReport> gpu;
  // --compare.
  struct Compare {
    std::string backend;
    double seconds = 0;
    gplanner::CheckerComparison comparison;
    std::optional<GpuCallReport> gpu;
  };
  std::optional<Compare> compare;
  std::string written;  // --out FILE, once written

  double collision_fraction() const { return n ? static_cast<double>(collisions) / n : 0.0; }
  double queries_per_second() const { return seconds > 0 ? n / seconds : 0.0; }
  // Whether --compare found the band broken (exit 3).
  bool band_broken() const;

  // The lines gplan check prints (each ends in a newline).
  std::string text() const;
  // The --json line's object.
  nlohmann::ordered_json json() const;
};

}  // namespace gplan

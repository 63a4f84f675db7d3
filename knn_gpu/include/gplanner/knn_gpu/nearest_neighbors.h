#pragma once
// k nearest neighbours of configurations under the planner's metric
// (configuration_metric.h): every point's neighbours among n points at once, on the GPU
// and with an exact CPU reference, plus separate query points (start, goal) on the CPU.
// Flat arrays in and out; plain C++: no CUDA headers, no Eigen, YAML or OMPL.
//
// Conventions shared by every function here: a point is one configuration row (shape
// [metric.width()]); row i of the result lists the k nearest points, sorted by
// increasing distance, on equal distance by increasing index; a point is never its own
// neighbour (all-points calls); only points within `radius` (distance <= radius) count,
// and a row with fewer than k of them is padded with index -1 and distance +inf.

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"

namespace gplanner {

// The largest k the GPU search supports (each lane keeps its k best in registers).
constexpr int kMaxGpuNeighbors = 64;

// Radius meaning "no bound".
constexpr float kUnboundedRadius = std::numeric_limits<float>::infinity();

// The neighbours of `rows` points, k per row.
struct NeighborTable {
  int k = 0;
  std::size_t rows = 0;
  std::vector<int> indices;      // shape [rows, k]; -1 pads
  std::vector<float> distances;  // shape [rows, k]; +inf pads

  int index(std::size_t row, int rank) const { return indices[row * k + rank]; }
  float distance(std::size_t row, int rank) const { return distances[row * k + rank]; }
  // How many neighbours row `row` has (k, or fewer where padded).
  int count(std::size_t row) const;
};

// CPU reference, all points: the k nearest neighbours of each of the n points among the
// others, by exact brute force over `threads` std::threads (0: all hardware threads).
// points: shape [n, metric.width()]. Throws std::invalid_argument for k < 1, a negative
// or NaN radius, or an invalid metric.
NeighborTable all_nearest_neighbors_cpu(const ConfigurationMetric& metric, const float* points,
                                        std::size_t n, int k, float radius = kUnboundedRadius,
                                        int threads = 0);

// CPU reference, separate queries: row i holds the k nearest of the n points to query i
// (no point is excluded). points: shape [n, width]; queries: shape [m, width].
NeighborTable nearest_neighbors_cpu(const ConfigurationMetric& metric, const float* points,
                                    std::size_t n, const float* queries, std::size_t m, int k,
                                    float radius = kUnboundedRadius, int threads = 0);

// Whether the GPU search can run here (built with CUDA and a device present); when not,
// says why in *reason (if given).
bool gpu_nearest_neighbors_available(std::string* reason = nullptr);

// What the last GpuNearestNeighbors::all_nearest() or nearest_rows() did.
struct GpuKnnStats {
  double milliseconds = 0;                 // GPU time of the whole call: upload to download
  double search_milliseconds = 0;          // the search kernel alone
  std::size_t tiles = 0;                   // points cut into tiles of 32 after the spatial sort
  int slices = 1;  // searches per query tile over disjoint candidate tiles, then merged
  unsigned long long tiles_visited = 0;    // candidate tiles loaded, over all query tiles
  unsigned long long candidate_pairs = 0;  // (point, candidate) pairs considered
  unsigned long long distance_evaluations = 0;  // exact metric evaluations among those
};

// All-points k nearest neighbours on the GPU: the points are sorted along a Morton curve
// through their leading metric coordinates, cut into tiles of 32 with bounding boxes, and
// one warp per tile searches candidate tiles outward along the curve, skipping those whose
// box lower-bounds the metric above its current k-th distance (and, for a floating base,
// candidates whose distance a bound without acos puts above it). Distances are
// configuration_distance() itself, so results equal the CPU reference up to ties.
class GpuNearestNeighbors {
 public:
  // On CUDA device `device` (numbered among those the process sees). Throws
  // std::runtime_error when no GPU can be used, or not that one (or the library was
  // built without CUDA), saying why.
  explicit GpuNearestNeighbors(int device = 0);
  ~GpuNearestNeighbors();
  GpuNearestNeighbors(const GpuNearestNeighbors&) = delete;
  GpuNearestNeighbors& operator=(const GpuNearestNeighbors&) = delete;

  // Same contract as all_nearest_neighbors_cpu(); points: host, shape [n, metric.width()].
  // Also throws std::invalid_argument for k > kMaxGpuNeighbors. Device buffers are kept
  // and reused between calls.
  NeighborTable all_nearest(const ConfigurationMetric& metric, const float* points, std::size_t n,
                            int k, float radius = kUnboundedRadius);

  // Rows [first, end) of all_nearest()'s indices alone, written to `indices` (host, shape
  // [end - first, k]): the same search, with only those rows and no distances brought
  // back (a roadmap's round needs its new milestones' neighbours among all). Throws as
  // all_nearest() does, and std::invalid_argument unless first <= end <= n. (Since 0.5.7.)
  void nearest_rows(const ConfigurationMetric& metric, const float* points, std::size_t n, int k,
                    std::size_t first, std::size_t end, int* indices,
                    float radius = kUnboundedRadius);
  const GpuKnnStats& last_stats() const;
  std::string device_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner

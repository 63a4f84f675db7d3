#pragma once
// k nearest neighbours of every roadmap milestone under the planner's metric: on the
// GPU (knn_gpu) when the planner runs the gpu backend and a GPU is there, otherwise the
// CPU reference on all host threads.

#include <memory>
#include <string>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"

namespace gplanner {

class NeighborFinder {
 public:
  virtual ~NeighborFinder() = default;
  // "gpu" or "cpu": where it runs.
  virtual std::string device() const = 0;
  // points: shape [n, metric.width()]; indices: shape [n, k], nearest first, the point
  // itself excluded, -1 where fewer than k others exist.
  virtual void all_nearest(const float* points, std::size_t n, int k,
                           std::vector<int>* indices) = 0;
};

// A GPU finder for backend "gpu" when a GPU can be used, else the CPU reference
// (`notice`, when given, says why in one line).
std::unique_ptr<NeighborFinder> make_neighbor_finder(const ConfigurationMetric& metric,
                                                     const std::string& backend,
                                                     std::string* notice = nullptr);

}  // namespace gplanner

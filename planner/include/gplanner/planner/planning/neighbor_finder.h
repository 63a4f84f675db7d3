#pragma once
// Nearest neighbours of new roadmap milestones under the planner's metric: on the GPU
// (knn_gpu, every milestone's neighbours at once) when the planner runs the gpu backend
// and a GPU is there, otherwise on the CPU: OMPL's GNAT, grown as milestones come, for
// rigid bodies (6 degrees of freedom or fewer), exact brute force on all threads for
// more, where GNAT's pruning fails (measured: neighbor_finder.cpp).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/knn_gpu/gpu_way_costs.h"

namespace gplanner {

class NeighborFinder {
 public:
  virtual ~NeighborFinder() = default;
  // "gpu" or "cpu": where it runs.
  virtual std::string device() const = 0;
  // points: shape [n, metric.width()], of which those given to earlier calls are in
  // the same order (a call with first 0, or fewer points than before, starts afresh).
  // indices: shape [end - first, k]: for each point in [first, end) its k nearest among
  // all n, nearest first, itself excluded, -1 where fewer than k others exist. The same
  // whatever ranges the new points are asked in. Returns false, with `indices` empty,
  // where the stop (set_stop) ended the call first; the same call made again goes on
  // from where it stopped.
  virtual bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end,
                          int k, std::vector<int>* indices) = 0;
  // The points [first_new, n) in one call.
  bool nearest_of_new(const float* points, std::size_t n, std::size_t first_new, int k,
                      std::vector<int>* indices) {
    return nearest_of(points, n, first_new, n, k, indices);
  }
  // Whether a call costs a search of all n points whatever its range (the GPU's):
  // callers then ask for all new points at once rather than in parts.
  virtual bool searches_all_points() const { return false; }
  // The cost of one query among n points, in the units of a query among few: 1 for a
  // tree search, n for brute force (callers size their parts by it).
  virtual double query_cost(std::size_t /*n*/) const { return 1; }
  // GPU calls made so far (as CollisionChecker::device_calls).
  virtual std::size_t device_calls() const { return 0; }
  // Where the roadmap's costs to the goal are computed on the GPU (GoalDistances::set_gpu):
  // the GPU finder's device, its calls counted in device_calls(); nullptr on the CPU
  // (since 0.5.3).
  virtual GpuWayCosts* way_costs() { return nullptr; }
  // Forgets every point given so far (a new roadmap follows).
  virtual void reset() {}
  // Polled during long work that is not a search (GNAT's insertions).
  void set_stop(std::function<bool()> stop) { stop_ = std::move(stop); }

 protected:
  bool should_stop() const { return stop_ && stop_(); }

 private:
  std::function<bool()> stop_;
};

// The GPU finder for backend "gpu" when a GPU can be used (on CUDA device `device`: the
// checker's, CollisionChecker::gpu_device, where it is one), else the CPU one (`notice`,
// when given, then says why in one line).
std::unique_ptr<NeighborFinder> make_neighbor_finder(const ConfigurationMetric& metric,
                                                     const std::string& backend,
                                                     std::string* notice = nullptr, int device = 0);

}  // namespace gplanner

#include "gplanner/planner/neighbor_finder.h"

#include <ompl/datastructures/NearestNeighborsGNAT.h>

#include <algorithm>

#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace gplanner {
namespace {

// OMPL's GNAT over point indices, the points read from the caller's array at each call.
class CpuNeighborFinder : public NeighborFinder {
 public:
  explicit CpuNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) { reset(); }
  std::string device() const override { return "cpu"; }

  void nearest_of_new(const float* points, std::size_t n, std::size_t first_new, int k,
                      std::vector<int>* indices) override {
    points_ = points;
    if (first_new < added_) reset();
    for (std::size_t i = added_; i < n; ++i) tree_->add(static_cast<std::uint32_t>(i));
    added_ = n;
    indices->assign((n - first_new) * k, -1);
    std::vector<std::uint32_t> found;
    for (std::size_t i = first_new; i < n; ++i) {
      tree_->nearestK(static_cast<std::uint32_t>(i), k + 1, found);
      int rank = 0;
      for (const std::uint32_t j : found) {
        if (j == i || rank == k) continue;
        (*indices)[(i - first_new) * k + rank++] = static_cast<int>(j);
      }
    }
  }

 private:
  void reset() {
    tree_ = std::make_unique<ompl::NearestNeighborsGNAT<std::uint32_t>>();
    tree_->setDistanceFunction([this](const std::uint32_t& a, const std::uint32_t& b) {
      const int w = metric_.width();
      return static_cast<double>(configuration_distance(metric_, points_ + std::size_t(a) * w,
                                                        points_ + std::size_t(b) * w));
    });
    added_ = 0;
  }

  ConfigurationMetric metric_;
  const float* points_ = nullptr;
  std::size_t added_ = 0;
  std::unique_ptr<ompl::NearestNeighborsGNAT<std::uint32_t>> tree_;
};

// knn_gpu's all-points search, every call over all points.
class GpuNeighborFinder : public NeighborFinder {
 public:
  explicit GpuNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) {}
  std::string device() const override { return "gpu"; }
  void nearest_of_new(const float* points, std::size_t n, std::size_t first_new, int k,
                      std::vector<int>* indices) override {
    const NeighborTable table = gpu_.all_nearest(metric_, points, n, k);
    indices->assign(table.indices.begin() + first_new * k, table.indices.end());
  }

 private:
  ConfigurationMetric metric_;
  GpuNearestNeighbors gpu_;
};

}  // namespace

std::unique_ptr<NeighborFinder> make_neighbor_finder(const ConfigurationMetric& metric,
                                                     const std::string& backend,
                                                     std::string* notice) {
  if (backend == "gpu") {
    std::string reason;
    if (gpu_nearest_neighbors_available(&reason))
      return std::make_unique<GpuNeighborFinder>(metric);
    if (notice) *notice = "k-NN runs on the CPU: " + reason;
  }
  return std::make_unique<CpuNeighborFinder>(metric);
}

}  // namespace gplanner

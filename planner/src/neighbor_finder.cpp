#include "gplanner/planner/neighbor_finder.h"

#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace gplanner {
namespace {

class CpuNeighborFinder : public NeighborFinder {
 public:
  explicit CpuNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) {}
  std::string device() const override { return "cpu"; }
  void all_nearest(const float* points, std::size_t n, int k, std::vector<int>* indices) override {
    *indices = all_nearest_neighbors_cpu(metric_, points, n, k).indices;
  }

 private:
  ConfigurationMetric metric_;
};

class GpuNeighborFinder : public NeighborFinder {
 public:
  explicit GpuNeighborFinder(const ConfigurationMetric& metric) : metric_(metric) {}
  std::string device() const override { return "gpu"; }
  void all_nearest(const float* points, std::size_t n, int k, std::vector<int>* indices) override {
    *indices = gpu_.all_nearest(metric_, points, n, k).indices;
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
    if (gpu_nearest_neighbors_available(&reason)) return std::make_unique<GpuNeighborFinder>(metric);
    if (notice) *notice = "k-NN runs on the CPU: " + reason;
  }
  return std::make_unique<CpuNeighborFinder>(metric);
}

}  // namespace gplanner

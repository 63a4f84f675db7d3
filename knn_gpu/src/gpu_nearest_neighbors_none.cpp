// The GPU k-NN search in a build without CUDA: it cannot be constructed.
#include <stdexcept>

#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace gplanner {

bool gpu_nearest_neighbors_available(std::string* reason) {
  if (reason) *reason = "gplanner was built without CUDA";
  return false;
}

struct GpuNearestNeighbors::Impl {
  GpuKnnStats stats;
};

GpuNearestNeighbors::GpuNearestNeighbors(int) {
  throw std::runtime_error(
      "GPU k-NN: gplanner was built without CUDA; use all_nearest_neighbors_cpu()");
}

GpuNearestNeighbors::~GpuNearestNeighbors() = default;

NeighborTable GpuNearestNeighbors::all_nearest(const ConfigurationMetric&, const float*,
                                               std::size_t, int, float) {
  throw std::runtime_error(
      "GPU k-NN: gplanner was built without CUDA; use all_nearest_neighbors_cpu()");
}

void GpuNearestNeighbors::nearest_rows(const ConfigurationMetric&, const float*, std::size_t, int,
                                       std::size_t, std::size_t, int*, float) {
  throw std::runtime_error(
      "GPU k-NN: gplanner was built without CUDA; use all_nearest_neighbors_cpu()");
}

const GpuKnnStats& GpuNearestNeighbors::last_stats() const { return impl_->stats; }

std::string GpuNearestNeighbors::device_name() const { return ""; }

}  // namespace gplanner

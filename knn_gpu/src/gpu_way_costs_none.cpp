// GpuWayCosts where gplanner is built without CUDA: never available.

#include <stdexcept>

#include "gplanner/knn_gpu/gpu_way_costs.h"

namespace gplanner {

struct GpuWayCosts::Impl {};

bool gpu_way_costs_available(std::string* reason) {
  if (reason) *reason = "gplanner was built without CUDA";
  return false;
}

GpuWayCosts::GpuWayCosts(int /*device*/) {
  throw std::runtime_error("GPU way costs: gplanner was built without CUDA");
}

GpuWayCosts::~GpuWayCosts() = default;

void GpuWayCosts::set_roadmap(std::uint64_t, const std::size_t*, std::size_t, const WayEdge*,
                              std::size_t) {}
std::uint64_t GpuWayCosts::roadmap_key() const { return 0; }

GpuWayCosts::Outcome GpuWayCosts::compute(std::uint32_t, const std::uint8_t*, double*,
                                          std::uint32_t*, const std::function<bool()>&) {
  return Outcome::kStopped;  // never made: the constructor throws
}

std::size_t GpuWayCosts::calls() const { return 0; }
std::size_t GpuWayCosts::last_rounds() const { return 0; }

}  // namespace gplanner

// The GPU checker in a build without CUDA: it cannot be constructed.
#include <stdexcept>

#include "gplanner/collision_gpu/gpu_batch_checker.h"

namespace gplanner {

struct GpuBatchChecker::Impl {};

GpuBatchChecker::GpuBatchChecker(const CollisionModel&, const GpuCheckerOptions&) {
  throw std::runtime_error("gplanner was built without CUDA");
}

GpuBatchChecker::~GpuBatchChecker() = default;

void GpuBatchChecker::release() {}

void GpuBatchChecker::check(const float*, std::size_t, std::uint8_t*, const float*) {
  throw std::runtime_error("gplanner was built without CUDA");
}

GpuCheckStats GpuBatchChecker::last_stats() const { return last_stats_; }

std::string GpuBatchChecker::device_name() const { return ""; }

std::vector<int> GpuBatchChecker::devices() const { return {}; }

}  // namespace gplanner

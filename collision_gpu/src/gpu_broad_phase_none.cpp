// The GPU broad phase in a build without CUDA: it cannot be constructed.
#include <stdexcept>

#include "gplanner/collision_gpu/gpu_broad_phase.h"

namespace gplanner {

bool gpu_broad_phase_available(std::string* reason) {
  if (reason) *reason = "gplanner was built without CUDA";
  return false;
}

struct GpuBroadPhase::Impl {
  GpuBroadPhaseStats stats;
};

GpuBroadPhase::GpuBroadPhase() {
  throw std::runtime_error(
      "GPU broad phase: gplanner was built without CUDA; use all_pairs_cpu() or "
      "sort_sweep_cpu()");
}

GpuBroadPhase::~GpuBroadPhase() = default;

void GpuBroadPhase::find_pairs(BroadPhaseMethod, const SphereArrays&, std::vector<SpherePair>*) {
  throw std::runtime_error("GPU broad phase: gplanner was built without CUDA");
}

const GpuBroadPhaseStats& GpuBroadPhase::last_stats() const { return impl_->stats; }

std::string GpuBroadPhase::device_name() const { return ""; }

}  // namespace gplanner

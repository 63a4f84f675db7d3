#include "gplanner/planner/checkers/checker_factory.h"

#include <algorithm>
#include <stdexcept>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"

namespace gplanner {

std::vector<std::string> collision_backends() { return {"gpu", "cpu", "fcl"}; }

std::unique_ptr<CollisionChecker> make_collision_checker(const Scene& scene,
                                                         const std::string& backend,
                                                         const CheckerOptions& options,
                                                         std::string* notice) {
  if (backend == "gpu") {
    // No GPU at all: the cpu backend, said. A device that is not there while others are
    // (a typo, or CUDA_VISIBLE_DEVICES) is the caller's error.
    const int device = options.gpu.device;
    const GpuDevice gpu = query_gpu_device(std::max(device, 0));
    if (gpu.count > 0 && device != GpuCheckerOptions::kAllDevices && !gpu.available)
      throw std::invalid_argument("the gpu backend: " + gpu.reason);
    if (gpu.available) return std::make_unique<GpuChecker>(scene, options.gpu, options.threads);
    if (notice) *notice = "no GPU (" + gpu.reason + "): the cpu backend runs instead";
    return std::make_unique<CpuChecker>(scene, options.threads);
  }
  if (backend == "fcl") return std::make_unique<FclChecker>(scene, options.threads);
  if (backend == "cpu") return std::make_unique<CpuChecker>(scene, options.threads);
  std::string known;
  for (const std::string& name : collision_backends()) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("'" + backend + "' is not a collision backend; use one of: " + known);
}

}  // namespace gplanner

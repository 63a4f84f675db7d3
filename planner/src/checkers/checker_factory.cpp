#include "gplanner/planner/checkers/checker_factory.h"

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
    const GpuDevice device = query_gpu_device();
    if (device.available) return std::make_unique<GpuChecker>(scene, options.gpu, options.threads);
    if (notice) *notice = "no GPU (" + device.reason + "): the cpu backend runs instead";
    return std::make_unique<CpuChecker>(scene, options.threads);
  }
  if (backend == "fcl") return std::make_unique<FclChecker>(scene, options.threads);
  if (backend == "cpu") return std::make_unique<CpuChecker>(scene, options.threads);
  std::string known;
  for (const std::string& name : collision_backends()) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("'" + backend + "' is not a collision backend; use one of: " + known);
}

}  // namespace gplanner

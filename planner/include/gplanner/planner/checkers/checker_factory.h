#pragma once
// Backends by name, for the command line and the OMPL adapters.

#include <memory>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/planner/checkers/collision_checker.h"

namespace gplanner {

struct CheckerOptions {
  int threads = 0;        // host threads for CPU backends; 0: all cores
  GpuCheckerOptions gpu;  // traversal, memory cap and device of the gpu backend
};

// Names accepted by make_collision_checker.
std::vector<std::string> collision_backends();

// The checker for `backend`; throws std::invalid_argument naming the known backends
// when the name is unknown. `scene` must outlive the checker. When `gpu` is asked for
// and no GPU can be used, the cpu backend runs instead and `notice` (when given) says
// why in one line; the checker's backend() always names what runs. A GPU device
// (options.gpu.device) that the process does not see, where it sees others, throws
// std::invalid_argument saying which it sees.
std::unique_ptr<CollisionChecker> make_collision_checker(const Scene& scene,
                                                         const std::string& backend,
                                                         const CheckerOptions& options = {},
                                                         std::string* notice = nullptr);

}  // namespace gplanner

#include "gplanner/planner/ompl/checker_factory.h"

#include <ompl/util/Console.h>

namespace gplanner::ompl_adapters {

std::unique_ptr<CollisionChecker> make_collision_checker(const Scene& scene,
                                                         const std::string& backend,
                                                         const CheckerOptions& options) {
  std::string notice;
  auto checker = gplanner::make_collision_checker(scene, backend, options, &notice);
  if (!notice.empty()) OMPL_WARN("gplanner: %s", notice.c_str());
  return checker;
}

}  // namespace gplanner::ompl_adapters

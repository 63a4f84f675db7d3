#include "gplanner/planner/planning/path_recheck.h"

#include <cmath>
#include <cstdint>
#include <sstream>

#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

std::string path_recheck_problem(const Scene& scene, const std::vector<float>& path,
                                 double refinement, bool from_start_to_goal) {
  const std::size_t width = scene.space.width();
  const std::size_t m = width ? path.size() / width : 0;
  if (m < 2 || path.size() != m * width) return "the path has fewer than 2 waypoints";
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!std::isfinite(path[i])) return "waypoint " + std::to_string(i / width) + " is no configuration";
  }
  if (from_start_to_goal) {
    for (std::size_t k = 0; k < width; ++k) {
      if (std::abs(path[k] - scene.start[k]) > 1e-5f) return "the path does not begin at the start";
      if (std::abs(path[(m - 1) * width + k] - scene.goal[k]) > 1e-5f)
        return "the path does not end at the goal";
    }
  }
  FclChecker fcl(scene);
  std::vector<std::uint8_t> states(m);
  fcl.check(path.data(), m, states.data());
  for (std::size_t i = 0; i < m; ++i) {
    if (states[i]) return "waypoint " + std::to_string(i) + " collides";
  }
  LocalPlannerOptions fine;
  fine.resolution_fraction = scene.planner.edge_resolution / refinement;
  fine.max_displacement = scene.planner.max_displacement / refinement;
  LocalPlanner local(scene, &fcl, fine);
  std::vector<std::uint8_t> invalid(m - 1);
  local.check_motions(path.data(), path.data() + width, m - 1, invalid.data());
  for (std::size_t i = 0; i + 1 < m; ++i) {
    if (invalid[i]) {
      std::ostringstream problem;
      problem << "segment " << i << " (waypoints " << i << " to " << i + 1 << ") collides at 1/"
              << refinement << " of the edge resolution";
      return problem.str();
    }
  }
  return "";
}

}  // namespace gplanner

#include "gplanner/planner/checkers/collision_checker.h"

#include <cmath>
#include <vector>

#include "gplanner/planner/checkers/collision_report.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

void check_start_and_goal(const Scene& scene, CollisionChecker* checker) {
  const char* what[2] = {"start", "goal"};
  const SourceLocation* where[2] = {&scene.start_defined, &scene.goal_defined};
  const std::vector<float>* q[2] = {&scene.start, &scene.goal};
  for (int k = 0; k < 2; ++k) {
    if (checker->in_collision(q[k]->data())) {
      const CollisionPair pair = CollisionReporter(scene).first_pair(q[k]->data());
      const std::string which = pair.found ? pair.describe() + " collide" : pair.describe();
      throw InputError(*where[k], std::string(what[k]) + " configuration is in collision (" +
                                      checker->backend() + " backend): " + which +
                                      "; move it clear of the obstacles and of the robot's "
                                      "own links");
    }
  }
}

double first_collision_on_straight_line(const Scene& scene, CollisionChecker* checker,
                                        double step) {
  const std::size_t width = scene.space.width();
  const std::size_t samples = static_cast<std::size_t>(std::ceil(1.0 / step)) + 1;
  std::vector<float> batch(samples * width);
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / (samples - 1);
    scene.space.interpolate(scene.start.data(), scene.goal.data(), t, &batch[i * width]);
  }
  std::vector<std::uint8_t> verdicts(samples);
  checker->check(batch.data(), samples, verdicts.data());
  for (std::size_t i = 0; i < samples; ++i) {
    if (verdicts[i]) return static_cast<double>(i) / (samples - 1);
  }
  return -1;
}

}  // namespace gplanner

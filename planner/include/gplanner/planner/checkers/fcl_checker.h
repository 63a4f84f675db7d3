#pragma once
// The baseline and ground truth: FCL (OBBRSS, double) on all CPU cores. Robot links
// against the environment, and for articulated robots the checked link pairs against
// each other, with an AABB test first as FCL's broad phase does. Solid box, sphere and
// cylinder obstacles are FCL primitives (as MoveIt checks them); where FCL finds no
// collision, the collision core's containment rule on the same components decides
// whether a link lies inside a closed obstacle or link, or an obstacle inside a closed
// link (docs/design.md, "Solids"). Calls from any number of threads run in parallel:
// each chunk of a call poses FCL objects of its own, taken from a pool that grows to the
// most chunks ever in flight, over shared, read-only BVHs.

#include <memory>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

class FclChecker : public CollisionChecker {
 public:
  // Builds one BVH per link with collision geometry and one for all obstacles; keeps
  // a reference to `scene`, which must outlive the checker. threads = 0: all cores.
  explicit FclChecker(const Scene& scene, int threads = 0);
  ~FclChecker() override;

  std::string backend() const override { return "fcl"; }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override;
  // A pair closer than its clearance by FCL's distance (after its collision check).
  void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override;
  // The same with every body's clearance raised by `slack` metres (>= 0): the outer edge
  // of the tolerance band, for comparisons.
  void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                        double slack, std::uint8_t* verdicts);

  // Smallest distance (metres) from the robot to the environment and between checked
  // link pairs; 0 when the configuration collides. To a primitive with an allowance
  // (Obstacle::allowance_m), its distance less the allowance. shape: configurations
  // [n, width], distances [n].
  void distance(const float* configurations, std::size_t n, double* distances);

  int threads() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner

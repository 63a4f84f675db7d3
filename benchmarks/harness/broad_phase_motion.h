#pragma once
// The scene of the broad-phase study: n seeded spheres moving in straight lines in a box
// and bouncing off its walls, as the seed's spheres move between frames.

#include <cstdint>
#include <vector>

#include "harness/broad_phase_config.h"
#include "gplanner/collision_gpu/broad_phase.h"

namespace gplan {

class BouncingSpheres {
 public:
  // n spheres, radii uniform in the options' range, in a cube whose volume is theirs over
  // options.volume_fraction, each at a uniform place in it with a uniform direction and
  // a speed uniform up to options.speed mean radii per frame; all from `seed`.
  BouncingSpheres(std::size_t n, const BroadPhaseOptions& options, std::uint64_t seed);

  // One frame: every sphere moves by its velocity; one that would leave the box is
  // reflected off the wall.
  void step();

  gplanner::SphereArrays arrays() const { return {centers_.data(), radii_.data(), radii_.size()}; }
  double box_side() const { return side_; }

 private:
  std::vector<float> centers_;     // shape [n, 3]
  std::vector<float> radii_;       // shape [n]
  std::vector<float> velocities_;  // shape [n, 3], per frame
  float side_ = 0;
};

}  // namespace gplan

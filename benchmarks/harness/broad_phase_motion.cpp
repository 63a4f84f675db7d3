#include "harness/broad_phase_motion.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace gplan {

BouncingSpheres::BouncingSpheres(std::size_t n, const BroadPhaseOptions& options,
                                 std::uint64_t seed)
    : centers_(3 * n), radii_(n), velocities_(3 * n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius(options.radius_min, options.radius_max);
  double volume = 0, radius_sum = 0;
  for (float& r : radii_) {
    r = float(radius(rng));
    volume += 4.0 / 3.0 * M_PI * double(r) * r * r;
    radius_sum += r;
  }
  side_ = float(std::max(std::cbrt(volume / options.volume_fraction), 2.0 * options.radius_max));
  const double top_speed = options.speed * radius_sum / double(std::max<std::size_t>(n, 1));
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> normal(0, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = radii_[i];
    double direction[3], length = 0;
    do {
      length = 0;
      for (double& d : direction) {
        d = normal(rng);
        length += d * d;
      }
    } while (length < 1e-12);
    length = std::sqrt(length);
    const double speed = top_speed * unit(rng);
    for (int a = 0; a < 3; ++a) {
      centers_[3 * i + a] = float(r + unit(rng) * std::max(0.0, double(side_) - 2 * r));
      velocities_[3 * i + a] = float(speed * direction[a] / length);
    }
  }
}

void BouncingSpheres::step() {
  const std::size_t n = radii_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const float r = radii_[i];
    for (int a = 0; a < 3; ++a) {
      float& c = centers_[3 * i + a];
      float& v = velocities_[3 * i + a];
      c += v;
      if (c < r) {
        c = std::min(2 * r - c, side_ - r);
        v = -v;
      } else if (c > side_ - r) {
        c = std::max(2 * (side_ - r) - c, r);
        v = -v;
      }
    }
  }
}

}  // namespace gplan

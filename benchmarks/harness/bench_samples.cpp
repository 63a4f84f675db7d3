#include "harness/bench_samples.h"

#include <algorithm>
#include <stdexcept>

namespace gplan {
namespace {

// Uniform samples drawn per free state wanted before giving up on a scene.
constexpr std::size_t kAttemptsPerState = 1000;

}  // namespace

std::vector<float> uniform_states(const gplanner::Scene& scene, std::size_t count,
                                  std::uint64_t seed) {
  const std::size_t width = scene.space.width();
  std::vector<float> states(count * width);
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < count; ++i) scene.space.sample_uniform(&rng, &states[i * width]);
  return states;
}

std::vector<float> free_states(const gplanner::Scene& scene, gplanner::CollisionChecker* checker,
                               std::size_t count, std::mt19937_64* rng,
                               const std::function<bool()>& stop, const std::string& who,
                               const std::string& fewer) {
  const std::size_t width = scene.space.width();
  std::vector<float> found, batch;
  std::vector<std::uint8_t> colliding;
  std::size_t found_count = 0, attempts = 0;
  const std::size_t most_attempts = kAttemptsPerState * count;
  while (found_count < count) {
    if (stop && stop()) return {};
    if (attempts >= most_attempts) {
      throw std::runtime_error(scene.file + ": " + who + " found only " +
                               std::to_string(found_count) + " free milestones of the " +
                               std::to_string(count) + " asked for in " + std::to_string(attempts) +
                               " uniform samples (the free space is too small a part of the "
                               "configuration space); ask for fewer " +
                               fewer);
    }
    const std::size_t n =
        std::min(std::max<std::size_t>(2 * (count - found_count), 1024), most_attempts - attempts);
    batch.resize(n * width);
    colliding.resize(n);
    for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(rng, &batch[i * width]);
    checker->check(batch.data(), n, colliding.data());
    attempts += n;
    for (std::size_t i = 0; i < n && found_count < count; ++i) {
      if (colliding[i]) continue;
      found.insert(found.end(), batch.begin() + i * width, batch.begin() + (i + 1) * width);
      ++found_count;
    }
  }
  return found;
}

}  // namespace gplan

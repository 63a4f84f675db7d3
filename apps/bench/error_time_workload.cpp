#include "bench/error_time_workload.h"

#include <algorithm>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"

namespace gplan {
namespace {

// Uniform samples drawn per free milestone wanted before giving up on a scene.
constexpr std::size_t kAttemptsPerMilestone = 1000;

// The first `count` uniform samples `truth` finds free, shape [count, width]; empty when
// stopped.
std::vector<float> free_states(const gplanner::Scene& scene, gplanner::CollisionChecker* truth,
                               std::size_t count, std::mt19937_64* rng,
                               const std::function<bool()>& stop) {
  const std::size_t width = scene.space.width();
  std::vector<float> found, batch;
  std::vector<std::uint8_t> colliding;
  std::size_t found_count = 0, attempts = 0;
  const std::size_t most_attempts = kAttemptsPerMilestone * count;
  while (found_count < count) {
    if (stop && stop()) return {};
    if (attempts >= most_attempts) {
      throw std::runtime_error(scene.file + ": the study found only " +
                               std::to_string(found_count) + " free milestones of the " +
                               std::to_string(count) + " asked for in " +
                               std::to_string(attempts) +
                               " uniform samples; ask for fewer roadmap_milestones");
    }
    const std::size_t n = std::min(std::max<std::size_t>(2 * (count - found_count), 1024),
                                   most_attempts - attempts);
    batch.resize(n * width);
    colliding.resize(n);
    for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(rng, &batch[i * width]);
    truth->check(batch.data(), n, colliding.data());
    attempts += n;
    for (std::size_t i = 0; i < n && found_count < count; ++i) {
      if (colliding[i]) continue;
      found.insert(found.end(), batch.begin() + i * width, batch.begin() + (i + 1) * width);
      ++found_count;
    }
  }
  return found;
}

}  // namespace

std::vector<float> study_states(const gplanner::Scene& scene, std::size_t count,
                                std::uint64_t seed) {
  const std::size_t width = scene.space.width();
  std::vector<float> states(count * width);
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < count; ++i) scene.space.sample_uniform(&rng, &states[i * width]);
  return states;
}

StudyEdges study_edges(const gplanner::Scene& scene, gplanner::CollisionChecker* truth,
                       std::size_t milestones, int neighbors, std::size_t count,
                       std::uint64_t seed, const std::function<bool()>& stop) {
  const std::size_t width = scene.space.width();
  std::mt19937_64 rng(seed);
  const std::vector<float> points = free_states(scene, truth, milestones, &rng, stop);
  if (points.empty()) return {};
  const std::unique_ptr<gplanner::NeighborFinder> finder = gplanner::make_neighbor_finder(
      gplanner::make_metric(scene.space, scene.planner), "cpu");
  if (stop) finder->set_stop(stop);
  std::vector<int> nearest;
  if (!finder->nearest_of_new(points.data(), milestones, 0, neighbors, &nearest)) return {};
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < milestones; ++i) {
    for (int m = 0; m < neighbors; ++m) {
      const int j = nearest[i * neighbors + m];
      if (j < 0 || static_cast<std::size_t>(j) == i) continue;
      pairs.emplace_back(std::min<std::size_t>(i, j), std::max<std::size_t>(i, j));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::shuffle(pairs.begin(), pairs.end(), rng);
  pairs.resize(std::min(pairs.size(), count));
  StudyEdges edges;
  edges.count = pairs.size();
  edges.from.resize(edges.count * width);
  edges.to.resize(edges.count * width);
  for (std::size_t e = 0; e < edges.count; ++e) {
    std::copy_n(&points[pairs[e].first * width], width, &edges.from[e * width]);
    std::copy_n(&points[pairs[e].second * width], width, &edges.to[e * width]);
  }
  return edges;
}

}  // namespace gplan

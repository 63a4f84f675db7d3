#include "harness/error_time_workload.h"

#include <algorithm>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "harness/bench_samples.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"

namespace gplan {

StudyEdges study_edges(const gplanner::Scene& scene, gplanner::CollisionChecker* truth,
                       std::size_t milestones, int neighbors, std::size_t count, std::uint64_t seed,
                       const std::function<bool()>& stop) {
  const std::size_t width = scene.space.width();
  std::mt19937_64 rng(seed);
  const std::vector<float> points =
      free_states(scene, truth, milestones, &rng, stop, "the study", "roadmap_milestones");
  if (points.empty()) return {};
  const std::unique_ptr<gplanner::NeighborFinder> finder =
      gplanner::make_neighbor_finder(gplanner::make_metric(scene.space, scene.planner), "cpu");
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

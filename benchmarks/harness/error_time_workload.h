#pragma once
// The seeded workload of the error-against-time study (benchmarks/harness/error_time_study.h):
// edges like those of a roadmap (its states: bench_samples' uniform_states). It depends only on the
// scene, the counts and the seed, never on a checker under study, so every checker and every knob
// value answers the same states and edges.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace gplanner {
struct Scene;
class CollisionChecker;
}  // namespace gplanner

namespace gplan {

// Edges' two ends, shape [count, width] each.
struct StudyEdges {
  std::vector<float> from, to;
  std::size_t count = 0;
};

// Edges like a roadmap's: `milestones` uniform states that `truth` finds free (the first
// ones drawn from `seed`), each joined to its `neighbors` nearest under the scene's
// metric (the undirected edges once each), and `count` of those edges drawn from them
// with the seed (all of them when there are fewer). Their lengths are thus those of the
// k-NN edges of a roadmap of that many milestones. Returns no edges when `stop` said to
// stop; throws std::runtime_error when the free space is too small to find the
// milestones (fewer than 1 in 1000 samples free).
StudyEdges study_edges(const gplanner::Scene& scene, gplanner::CollisionChecker* truth,
                       std::size_t milestones, int neighbors, std::size_t count, std::uint64_t seed,
                       const std::function<bool()>& stop);

}  // namespace gplan

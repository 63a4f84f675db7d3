#include "planner/scene_test_support.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/local_planner.h"
#include "test_support.h"

namespace gplanner::testing {
namespace fs = std::filesystem;

std::vector<std::string> shipped_scene_files() {
  std::vector<std::string> files;
  const fs::path folder = fs::path(project_root()) / "scenes";
  if (fs::is_directory(folder)) {
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (entry.path().extension() == ".yaml") files.push_back(entry.path().filename().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<float> sample_configurations(const Scene& scene, std::size_t n,
                                         unsigned long long seed) {
  const std::size_t width = scene.space.width();
  std::vector<float> q(n * width);
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(&rng, &q[i * width]);
  return q;
}

std::string path_problem(const Scene& scene, const std::vector<float>& path) {
  const std::size_t width = scene.space.width();
  const std::size_t m = path.size() / width;
  if (m < 2 || path.size() != m * width) return "the path has fewer than 2 waypoints";
  for (std::size_t k = 0; k < width; ++k) {
    if (std::abs(path[k] - scene.start[k]) > 1e-5f) return "the path does not begin at the start";
    if (std::abs(path[(m - 1) * width + k] - scene.goal[k]) > 1e-5f)
      return "the path does not end at the goal";
  }
  FclChecker fcl(scene);
  std::vector<std::uint8_t> states(m);
  fcl.check(path.data(), m, states.data());
  for (std::size_t i = 0; i < m; ++i)
    if (states[i]) return "waypoint " + std::to_string(i) + " collides";
  LocalPlannerOptions fine;
  fine.resolution_fraction = scene.planner.number("edge_resolution") / 10;
  fine.max_displacement = scene.planner.number("max_displacement") / 10;
  LocalPlanner local(scene, &fcl, fine);
  std::vector<std::uint8_t> invalid(m - 1);
  local.check_motions(path.data(), path.data() + width, m - 1, invalid.data());
  for (std::size_t i = 0; i + 1 < m; ++i) {
    if (invalid[i]) {
      return "segment " + std::to_string(i) + " (waypoints " + std::to_string(i) + " to " +
             std::to_string(i + 1) + ") collides at a tenth of the edge resolution";
    }
  }
  return "";
}

std::string scene_test_name(const std::string& file) {
  std::string name = fs::path(file).stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

}  // namespace gplanner::testing

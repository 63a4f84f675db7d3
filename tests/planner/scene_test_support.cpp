#include "planner/scene_test_support.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "gplanner/planner/planning/path_recheck.h"
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
  return path_recheck_problem(scene, path, 10, /*from_start_to_goal=*/true);
}

std::string scene_test_name(const std::string& file) {
  std::string name = fs::path(file).stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

}  // namespace gplanner::testing

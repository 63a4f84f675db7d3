#pragma once
// Scenes for checker tests: the shipped ones, and random batches of configurations.

#include <random>
#include <string>
#include <vector>

#include "gplanner/planner/scene/scene.h"

namespace gplanner::testing {

// File names (not paths) of scenes/*.yaml, sorted.
std::vector<std::string> shipped_scene_files();

// n configurations sampled uniformly in the scene (shape: [n, width]), seeded.
std::vector<float> sample_configurations(const Scene& scene, std::size_t n,
                                         unsigned long long seed);

// Empty when the path (shape [waypoints, width]) starts at the scene's start, ends at
// its goal, and FCL finds every waypoint and every sample of every segment free, the
// segments sampled at a tenth of the scene's edge resolution; otherwise what is wrong.
std::string path_problem(const Scene& scene, const std::vector<float>& path);

// A gtest-safe parameter name for a scene file ("pr2_reach.yaml" -> "pr2_reach").
std::string scene_test_name(const std::string& file);

}  // namespace gplanner::testing

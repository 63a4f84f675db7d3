#pragma once
// Scenes for checker tests: the shipped ones, and random batches of configurations.

#include <random>
#include <string>
#include <vector>

#include "gplanner/planner/scene.h"

namespace gplanner::testing {

// File names (not paths) of scenes/*.yaml, sorted.
std::vector<std::string> shipped_scene_files();

// n configurations sampled uniformly in the scene (shape: [n, width]), seeded.
std::vector<float> sample_configurations(const Scene& scene, std::size_t n,
                                         unsigned long long seed);

// A gtest-safe parameter name for a scene file ("pr2_reach.yaml" -> "pr2_reach").
std::string scene_test_name(const std::string& file);

}  // namespace gplanner::testing

// StraightLine: the same floats as ConfigurationSpace::interpolate, bit for bit, on every
// kind of base (fixed, planar, floating) and with continuous joints.

#include "gplanner/planner/scene/straight_line.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

class StraightLineOn : public ::testing::TestWithParam<std::string> {};

TEST_P(StraightLineOn, GivesInterpolatesFloatsBitForBit) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  const ConfigurationSpace& space = scene.space;
  const int w = space.width();
  const std::vector<float> pool = testing::sample_configurations(scene, 400, 23);
  std::vector<double> ts = {0.0, 1e-3, 0.1, 0.25, 1.0 / 3, 0.5, 0.9, 1.0 - 1e-9, 1.0};
  for (int j = 1; j < 37; ++j) ts.push_back(static_cast<double>(j) / 37);
  StraightLine line;  // one line, reset for every motion
  std::vector<float> expected(w), got(w);
  int compared = 0;
  for (std::size_t i = 0; i + 1 < pool.size() / w; i += 2) {
    const float* a = &pool[i * w];
    const float* b = &pool[(i + 1) * w];
    line.reset(space, a, b);
    for (const double t : ts) {
      space.interpolate(a, b, t, expected.data());
      std::fill(got.begin(), got.end(), -7.0f);
      line.at(t, got.data());
      ASSERT_EQ(std::memcmp(expected.data(), got.data(), w * sizeof(float)), 0)
          << GetParam() << " motion " << i / 2 << " t " << t;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 200 * static_cast<int>(ts.size()));
}

// pr2_reach: a fixed base and continuous joints; pr2_base_arm: a planar base; the piano:
// a floating base alone; the humanoid: a floating base and 32 joints.
INSTANTIATE_TEST_SUITE_P(Scenes, StraightLineOn,
                         ::testing::Values("pr2_reach.yaml", "pr2_base_arm.yaml", "piano.yaml",
                                           "humanoid.yaml"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param.substr(0, info.param.find('.'));
                         });

}  // namespace
}  // namespace gplanner

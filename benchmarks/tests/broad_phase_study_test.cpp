// The broad-phase study's parts: the bouncing spheres stay in their box and are seeded,
// and the records make the CSV, the tables and the crossovers.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "harness/broad_phase_motion.h"
#include "harness/broad_phase_record.h"

namespace gplan {
namespace {

TEST(BroadPhaseStudy, SpheresBounceInsideTheirBoxAndAreSeeded) {
  BroadPhaseOptions options;
  options.radius_min = 0.2;
  options.radius_max = 0.8;
  options.speed = 2;  // fast: many bounces
  BouncingSpheres a(500, options, 7), b(500, options, 7), c(500, options, 8);
  EXPECT_EQ(std::vector<float>(a.arrays().centers, a.arrays().centers + 1500),
            std::vector<float>(b.arrays().centers, b.arrays().centers + 1500));
  EXPECT_NE(std::vector<float>(a.arrays().centers, a.arrays().centers + 1500),
            std::vector<float>(c.arrays().centers, c.arrays().centers + 1500));
  const double side = a.box_side();
  EXPECT_GT(side, 1.6);
  for (int frame = 0; frame < 200; ++frame) {
    a.step();
    const gplanner::SphereArrays s = a.arrays();
    for (std::size_t i = 0; i < s.n; ++i) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(s.centers[3 * i + k], s.radii[i] - 1e-4f) << "frame " << frame;
        ASSERT_LE(s.centers[3 * i + k], side - s.radii[i] + 1e-4f) << "frame " << frame;
      }
    }
  }
}

BroadPhasePoint point(std::uint64_t count, const std::string& method, double median_ms) {
  BroadPhasePoint p;
  p.count = count;
  p.method = method;
  if (median_ms > 0) {
    p.frames = 10;
    p.median_ms = p.mean_ms = p.min_ms = p.max_ms = median_ms;
    p.fps_mean = 1e3 / median_ms;
    p.pairs_mean = 3;
  } else {
    p.note = "above its max_count 64";
  }
  return p;
}

TEST(BroadPhaseStudy, CrossoversAndTables) {
  std::vector<BroadPhasePoint> points = {
      point(64, "cpu-all-pairs", 0.01),  point(64, "gpu-grid", 0.05),
      point(128, "cpu-all-pairs", 0.04), point(128, "gpu-grid", 0.05),
      point(256, "cpu-all-pairs", -1),   point(256, "gpu-grid", 0.06),
      point(320, "cpu-all-pairs", -1),   point(320, "gpu-grid", 0.07)};
  points[1].speedup = 0.2;
  EXPECT_EQ(broad_phase_crossovers(points),
            (std::vector<std::string>{"cpu-all-pairs: 64 to 128 spheres",
                                      "gpu-grid: 256 to 320 spheres"}));
  std::ostringstream csv;
  write_broad_phase_csv_header(csv);
  write_broad_phase_csv_line(csv, points[1]);
  write_broad_phase_csv_line(csv, points[4]);
  EXPECT_EQ(csv.str(),
            "count,method,frames,pairs_mean,mean_ms,median_ms,min_ms,max_ms,fps_mean,speedup,"
            "reruns,mismatches,note\n"
            "64,gpu-grid,10,3.000,0.05,0.05,0.05,0.05,20000,0.2,0,0,\n"
            "256,cpu-all-pairs,0,,,,,,,,0,0,above its max_count 64\n");
  std::ostringstream table;
  write_broad_phase_table(table, "mine", points, {"gpu-all-pairs left out: no GPU"});
  const std::string md = table.str();
  EXPECT_NE(md.find("| 64 | 59.31 | 36.49 | 0.62 | 100000 | - | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 256 | 3 | - | 0.06 | gpu-grid |"), std::string::npos) << md;
  EXPECT_NE(md.find("- cpu-all-pairs `-`: above its max_count 64"), std::string::npos) << md;
  EXPECT_NE(md.find("- gpu-grid: 256 to 320 spheres"), std::string::npos) << md;
  EXPECT_NE(md.find("- gpu-all-pairs left out: no GPU"), std::string::npos) << md;
}

}  // namespace
}  // namespace gplan

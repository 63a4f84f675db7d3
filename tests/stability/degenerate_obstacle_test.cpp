// Stability: degenerate triangles in an obstacle mesh beside real ones. The loader
// drops faces that repeat a vertex (after merging vertices at the same position, so a
// face of coincident corners goes too): such a face is a segment or a point. Faces of
// zero area with three distinct vertices (collinear corners) are kept, and checked as
// the segment they are: a zero-area face lying on a real edge of the mesh, and a
// "needle" of collinear faces sticking out of it, must both be seen by the checker.

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "test_support.h"

namespace gplanner {
namespace {

// A unit cube at the origin (12 faces) and degenerate faces:
// - f 1 1 2: a repeated index (dropped);
// - f 1 9 2 with vertex 9 at vertex 1's position: merged into a repeated index (dropped);
// - f 13 13 13 far away: a point (dropped);
// - f 1 10 2 with vertex 10 the midpoint of the edge 1-2: zero area on a real edge (kept);
// - f 11 12 13: three collinear points from the +x face's centre (0.5, 0, 0) out to
//   (1, 0, 0), a needle (kept). Vertex 13 is also the point face's corner.
const char* const kObstacleObj =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
    "v -0.5 -0.5 -0.5\nv 0 -0.5 -0.5\nv 0.5 0 0\nv 0.75 0 0\nv 1 0 0\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n"
    "f 1 1 2\nf 1 9 2\nf 13 13 13\nf 1 10 2\nf 11 12 13\n";

const char* const kRobotObj =
    "v -0.05 -0.05 -0.05\nv 0.05 -0.05 -0.05\nv 0.05 0.05 -0.05\nv -0.05 0.05 -0.05\n"
    "v -0.05 -0.05 0.05\nv 0.05 -0.05 0.05\nv 0.05 0.05 0.05\nv -0.05 0.05 0.05\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

Scene load(const testing::ScratchFolder& scratch) {
  scratch.write("obstacle.obj", kObstacleObj);
  scratch.write("robot.obj", kRobotObj);
  return load_scene(scratch.write(
      "scene.yaml",
      "name: degenerate\nrobot:\n  mesh: robot.obj\nobstacles:\n  - mesh: obstacle.obj\n"
      "bounds:\n  min: [-2, -2, -2]\n  max: [2, 2, 2]\n"
      "start:\n  base: {xyz: [-1.5, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n"
      "goal:\n  base: {xyz: [1.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}\n"));
}

TEST(StabilityDegenerateObstacles, LoaderDropsRepeatedVerticesAndKeepsZeroAreaFaces) {
  testing::ScratchFolder scratch;
  const Scene scene = load(scratch);
  ASSERT_EQ(scene.obstacles.size(), 1u);
  // 12 cube faces, the zero-area face on the edge and the needle.
  EXPECT_EQ(scene.obstacle_triangle_count(), 14u);
}

// The robot cube (side 0.1) placed by its centre, with its distance to the obstacle
// known by construction (from the float position actually passed).
struct Placement {
  const char* what;
  float x, y, z;
  double distance;  // 0: contact
};

std::vector<Placement> placements(double delta) {
  std::vector<Placement> out;
  for (const double gap : {-1e-2, 0.0, 0.5 * delta, 2 * delta, 1e-3}) {
    // Its -x face at x = 1 + gap: facing the needle's tip.
    const float tip = float(1.05 + gap);
    out.push_back({"at the needle's tip", tip, 0, 0, std::max(0.0, double(tip) - 0.05 - 1)});
    // Its -y face at y = gap, over the needle's middle (x from 0.8 to 0.9).
    const float side = float(0.05 + gap);
    out.push_back({"beside the needle", 0.85f, side, 0, std::max(0.0, double(side) - 0.05)});
    // Its top edge along x at y = z = -0.5 - gap: facing the cube's bottom edge 1-2,
    // on which the zero-area face lies, a distance sqrt(2) gap away.
    const float below = float(-0.55 - gap);
    const double d = std::max(0.0, -0.5 - (double(below) + 0.05));
    out.push_back({"off the edge with a zero-area face", 0, below, below, std::hypot(d, d)});
  }
  return out;
}

void expect_verdicts(const std::vector<std::string>& backends) {
  testing::ScratchFolder scratch;
  const Scene scene = load(scratch);
  const double delta = tolerance_delta(scene);
  for (const std::string& backend : backends) {
    auto checker = make_collision_checker(scene, backend);
    ASSERT_EQ(checker->backend(), backend);
    for (const Placement& p : placements(delta)) {
      const float q[7] = {p.x, p.y, p.z, 1, 0, 0, 0};
      const bool hit = checker->in_collision(q);
      const std::string what =
          backend + ", " + p.what + ", distance " + std::to_string(p.distance / delta) + " delta";
      if (backend == "fcl" && p.distance == 0) {
        // FCL on contacts with a degenerate face: recorded, not asserted.
        std::cout << what << ": " << (hit ? "collision" : "free") << "\n";
        continue;
      }
      if (p.distance == 0) EXPECT_TRUE(hit) << what << ": contact missed";
      if (p.distance > delta) EXPECT_FALSE(hit) << what << ": a collision outside the band";
    }
  }
}

TEST(StabilityDegenerateObstacles, ZeroAreaFacesAreSeenCpuAndFcl) {
  expect_verdicts({"cpu", "fcl"});
}

TEST(StabilityDegenerateObstacles, GpuSeesZeroAreaFaces) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_verdicts({"gpu"});
}

}  // namespace
}  // namespace gplanner

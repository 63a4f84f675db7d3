// Stability: contacts whose distance is known by construction (a cube robot against a
// cube obstacle, face to face, edge to edge and vertex to face), from deep penetration
// to separations far beyond the tolerance band, at model sizes from 0.1 mm to 10 km;
// every backend judged against the band: penetration must collide, a distance above
// delta must be free, in between either. The *Gpu* case runs the same on the GPU.

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/gpu_device.h"
#include "gplanner/planner/checker_factory.h"
#include "gplanner/planner/scene.h"
#include "gplanner/planner/scene_collision_model.h"
#include "test_support.h"

namespace gplanner {
namespace {

// kNeedle: the robot is one sliver triangle (1e-6 as wide as long) whose tip points at
// the obstacle's face; kSegment: one degenerate triangle, its three vertices on a line.
enum class Contact { kFaceFace, kEdgeEdge, kVertexFace, kNeedle, kSegment };

const char* name_of(Contact c) {
  switch (c) {
    case Contact::kFaceFace:
      return "face-face";
    case Contact::kEdgeEdge:
      return "edge-edge";
    case Contact::kVertexFace:
      return "vertex-face";
    case Contact::kNeedle:
      return "needle tip-face";
    case Contact::kSegment:
      return "degenerate tip-face";
  }
  return "";
}

// A cube of side `side` centred at its origin, as OBJ text.
std::string cube_obj(double side) {
  std::ostringstream out;
  out << std::setprecision(17);
  const double h = side / 2;
  for (int i = 0; i < 8; ++i)
    out << "v " << ((i & 1) ? h : -h) << ' ' << ((i & 2) ? h : -h) << ' ' << ((i & 4) ? h : -h)
        << "\n";
  out << "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
         "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  return out.str();
}

// The robot's mesh: the cube, or a single triangle with its tip at the origin reaching
// along +x (a sliver, or three points on a line).
std::string robot_obj(double side, Contact contact) {
  if (contact != Contact::kNeedle && contact != Contact::kSegment) return cube_obj(side);
  std::ostringstream out;
  out << std::setprecision(17) << "v 0 0 0\n";
  if (contact == Contact::kNeedle) {
    out << "v " << side << ' ' << -0.5e-6 * side << " 0\nv " << side << ' ' << 0.5e-6 * side
        << " 0\n";
  } else {
    out << "v " << side / 2 << " 0 0\nv " << side << " 0 0\n";
  }
  out << "f 1 2 3\n";
  return out.str();
}

// The scene: the obstacle cube at the origin (turned 45 degrees about y for edge-edge
// contact, so that an edge along y faces +x), the robot a cube of the same size.
std::string scene_yaml(double side, Contact contact) {
  std::ostringstream out;
  out << std::setprecision(17);
  const double s = std::sin(M_PI / 8), c = std::cos(M_PI / 8);
  out << "name: contact\nrobot:\n  mesh: cube.obj\nobstacles:\n  - box: [" << side << ", " << side
      << ", " << side << "]\n";
  if (contact == Contact::kEdgeEdge)
    out << "    pose: {quat_wxyz: [" << c << ", 0, " << s << ", 0]}\n";
  out << "bounds:\n  min: [" << -4 * side << ", " << -4 * side << ", " << -4 * side << "]\n  max: ["
      << 4 * side << ", " << 4 * side << ", " << 4 * side << "]\n"
      << "start:\n  base: {xyz: [" << -3 * side << ", 0, 0], quat_wxyz: [1, 0, 0, 0]}\n"
      << "goal:\n  base: {xyz: [" << 3 * side << ", 0, 0], quat_wxyz: [1, 0, 0, 0]}\n";
  return out.str();
}

// The robot's pose at distance `gap` (negative: penetration) from the obstacle on +x.
std::vector<float> pose_at(double side, Contact contact, double gap) {
  double x = 0, qw = 1, qx = 0, qy = 0, qz = 0;
  if (contact == Contact::kNeedle || contact == Contact::kSegment) {
    x = side / 2 + gap;  // the tip, at the robot's origin
  } else if (contact == Contact::kFaceFace) {
    x = side + gap;
  } else if (contact == Contact::kEdgeEdge) {
    // Turned 45 degrees about z: an edge along z faces -x, crossing the obstacle's edge.
    x = std::sqrt(2.0) * side + gap;
    qw = std::cos(M_PI / 8);
    qz = std::sin(M_PI / 8);
  } else {
    // The vertex (-1, -1, -1) turned onto -x: rotation about (0, 1, -1) / sqrt(2) by the
    // angle between them.
    x = side / 2 + std::sqrt(3.0) * side / 2 + gap;
    const double angle = std::acos(1 / std::sqrt(3.0));
    qw = std::cos(angle / 2);
    qy = std::sin(angle / 2) / std::sqrt(2.0);
    qz = -std::sin(angle / 2) / std::sqrt(2.0);
  }
  return {static_cast<float>(x),
          0,
          0,
          static_cast<float>(qw),
          static_cast<float>(qx),
          static_cast<float>(qy),
          static_cast<float>(qz)};
}

void expect_within_band(const std::vector<std::string>& backends) {
  std::size_t collisions = 0, free = 0, in_band_collisions = 0, in_band = 0;
  for (const double side : {1e-4, 1e-2, 1.0, 1e2, 1e4}) {
    for (const Contact contact : {Contact::kFaceFace, Contact::kEdgeEdge, Contact::kVertexFace,
                                  Contact::kNeedle, Contact::kSegment}) {
      testing::ScratchFolder scratch;
      scratch.write("cube.obj", robot_obj(side, contact));
      const Scene scene = load_scene(scratch.write("scene.yaml", scene_yaml(side, contact)));
      const double delta = tolerance_delta(scene);
      // Gaps: relative to the model from 1e-7 to 1e-2, and around delta.
      std::vector<double> gaps = {-0.1 * side, -1e-3 * side, -2 * delta,  0.5 * delta,
                                  2 * delta,   10 * delta,   1e-3 * side, 1e-2 * side};
      for (double r = 1e-7; r <= 1e-2; r *= 10) gaps.push_back(r * side);
      for (const std::string& backend : backends) {
        std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
        ASSERT_EQ(checker->backend(), backend);
        for (const double gap : gaps) {
          const std::vector<float> q = pose_at(side, contact, gap);
          const bool hit = checker->in_collision(q.data());
          const std::string what = backend + " " + name_of(contact) + ", side " +
                                   std::to_string(side) + " m, gap " + std::to_string(gap / delta) +
                                   " delta";
          if (gap < 0) EXPECT_TRUE(hit) << what << ": a penetration reported free";
          if (gap > delta) EXPECT_FALSE(hit) << what << ": a collision outside the band";
          if (gap >= 0 && gap <= delta) {
            ++in_band;
            in_band_collisions += hit;
          }
          (hit ? collisions : free) += 1;
        }
      }
    }
  }
  // Every backend met both kinds of answer; within the band either is allowed.
  EXPECT_GT(collisions, 0u);
  EXPECT_GT(free, 0u);
  EXPECT_GT(in_band, 0u);
  std::cout << "within the band: " << in_band_collisions << " of " << in_band
            << " reported as collisions\n";
}

TEST(StabilityContacts, CpuAndFclKeepTheBand) { expect_within_band({"cpu", "fcl"}); }

TEST(StabilityContacts, GpuKeepsTheBand) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_within_band({"gpu"});
}

}  // namespace
}  // namespace gplanner

#pragma once
// Contacts whose distance is known by construction, shared by the stability tests: a
// cube robot (or one sliver or degenerate triangle) against a cube obstacle, face to
// face, edge to edge and vertex to face, at a chosen gap (negative: penetration), the
// whole scene placed anywhere in the world. Every backend is judged against the band:
// penetration must collide, a distance above delta must be free, in between either.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "test_support.h"

namespace gplanner::testing {

// kNeedle: the robot is one sliver triangle (1e-6 as wide as long) whose tip points at
// the obstacle's face; kSegment: one degenerate triangle, its three vertices on a line.
enum class Contact { kFaceFace, kEdgeEdge, kVertexFace, kNeedle, kSegment };

inline const Contact kAllContacts[] = {Contact::kFaceFace, Contact::kEdgeEdge, Contact::kVertexFace,
                                       Contact::kNeedle, Contact::kSegment};

inline const char* name_of(Contact c) {
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
inline std::string cube_obj(double side) {
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
inline std::string robot_obj(double side, Contact contact) {
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

// The scene: the obstacle cube at p_WO (turned 45 degrees about y for edge-edge
// contact, so that an edge along y faces +x), the robot a cube of the same size,
// bounds 4 sides either way of the obstacle.
inline std::string contact_scene_yaml(double side, Contact contact,
                                      const Eigen::Vector3d& p_WO = Eigen::Vector3d::Zero()) {
  std::ostringstream out;
  out << std::setprecision(17);
  const double s = std::sin(M_PI / 8), c = std::cos(M_PI / 8);
  auto point = [&](double dx) {
    std::ostringstream p;
    p << std::setprecision(17) << p_WO.x() + dx * side << ", " << p_WO.y() << ", " << p_WO.z();
    return p.str();
  };
  auto corner = [&](double k) {
    std::ostringstream p;
    p << std::setprecision(17) << p_WO.x() + k * side << ", " << p_WO.y() + k * side << ", "
      << p_WO.z() + k * side;
    return p.str();
  };
  out << "name: contact\nrobot:\n  mesh: cube.obj\nobstacles:\n  - box: [" << side << ", " << side
      << ", " << side << "]\n";
  const bool turned = contact == Contact::kEdgeEdge, moved = !p_WO.isZero();
  if (turned || moved) {
    out << "    pose: {";
    if (moved) out << "xyz: [" << point(0) << "]" << (turned ? ", " : "");
    if (turned) out << "quat_wxyz: [" << c << ", 0, " << s << ", 0]";
    out << "}\n";
  }
  out << "bounds:\n  min: [" << corner(-4) << "]\n  max: [" << corner(4) << "]\n"
      << "start:\n  base: {xyz: [" << point(-3) << "], quat_wxyz: [1, 0, 0, 0]}\n"
      << "goal:\n  base: {xyz: [" << point(3) << "], quat_wxyz: [1, 0, 0, 0]}\n";
  return out.str();
}

// The robot's pose (x y z qw qx qy qz, in double) at distance `gap` (negative:
// penetration) from the obstacle at p_WO, on +x.
inline std::vector<double> contact_pose(double side, Contact contact, double gap,
                                        const Eigen::Vector3d& p_WO = Eigen::Vector3d::Zero()) {
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
  return {p_WO.x() + x, p_WO.y(), p_WO.z(), qw, qx, qy, qz};
}

// Gaps: relative to the model from 1e-7 to 1e-2, and around delta.
inline std::vector<double> contact_gaps(double side, double delta) {
  std::vector<double> gaps = {-0.1 * side, -1e-3 * side, -2 * delta,  0.5 * delta,
                              2 * delta,   10 * delta,   1e-3 * side, 1e-2 * side};
  for (double r = 1e-7; r <= 1e-2; r *= 10) gaps.push_back(r * side);
  return gaps;
}

// What the contact cases found, summed over backends and cases.
struct BandTally {
  std::size_t collisions = 0, free = 0, in_band = 0, in_band_collisions = 0;
};

// Every contact at every gap, for model sizes `sides`, the obstacle at p_WO, on each
// backend: penetration must collide, a distance above delta must be free. The rows
// are made from world poses by the scene (ConfigurationSpace::from_file_values).
inline BandTally expect_contacts_within_band(
    const std::vector<std::string>& backends, const std::vector<double>& sides,
    const Eigen::Vector3d& p_WO = Eigen::Vector3d::Zero()) {
  BandTally tally;
  for (const double side : sides) {
    for (const Contact contact : kAllContacts) {
      ScratchFolder scratch;
      scratch.write("cube.obj", robot_obj(side, contact));
      const Scene scene =
          load_scene(scratch.write("scene.yaml", contact_scene_yaml(side, contact, p_WO)));
      const double delta = tolerance_delta(scene);
      for (const std::string& backend : backends) {
        std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
        EXPECT_EQ(checker->backend(), backend);
        if (checker->backend() != backend) return tally;
        for (const double gap : contact_gaps(side, delta)) {
          const std::vector<double> pose = contact_pose(side, contact, gap, p_WO);
          std::vector<float> q(7);
          scene.space.from_file_values(pose.data(), q.data());
          const bool hit = checker->in_collision(q.data());
          const std::string what = backend + " " + name_of(contact) + ", side " +
                                   std::to_string(side) + " m, gap " + std::to_string(gap / delta) +
                                   " delta, obstacle at " + std::to_string(p_WO.norm()) + " m";
          if (gap < 0) EXPECT_TRUE(hit) << what << ": a penetration reported free";
          if (gap > delta) EXPECT_FALSE(hit) << what << ": a collision outside the band";
          if (gap >= 0 && gap <= delta) {
            ++tally.in_band;
            tally.in_band_collisions += hit;
          }
          (hit ? tally.collisions : tally.free) += 1;
        }
      }
    }
  }
  // Every backend met both kinds of answer; within the band either is allowed.
  EXPECT_GT(tally.collisions, 0u);
  EXPECT_GT(tally.free, 0u);
  EXPECT_GT(tally.in_band, 0u);
  std::cout << "within the band: " << tally.in_band_collisions << " of " << tally.in_band
            << " reported as collisions\n";
  return tally;
}

}  // namespace gplanner::testing

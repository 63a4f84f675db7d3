#include "gplanner/planner/scene/robot_model.h"

#include <algorithm>
#include <set>

#include "gplanner/planner/scene/mesh_components.h"

namespace gplanner {

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::kFixed:
      return "fixed";
    case JointType::kRevolute:
      return "revolute";
    case JointType::kContinuous:
      return "continuous";
    case JointType::kPrismatic:
      return "prismatic";
    case JointType::kFloating:
      return "floating";
    case JointType::kPlanar:
      return "planar";
  }
  return "unknown";
}

int RobotModel::find_link(const std::string& link_name) const {
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].name == link_name) return static_cast<int>(i);
  }
  return -1;
}

int RobotModel::find_joint(const std::string& joint_name) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == joint_name) return static_cast<int>(i);
  }
  return -1;
}

std::size_t RobotModel::triangle_count() const {
  std::size_t count = 0;
  for (const Link& link : links) count += link.collision.triangle_count();
  return count;
}

std::vector<std::pair<int, int>> RobotModel::checked_pairs() const {
  const std::set<std::pair<int, int>> disabled(disabled_pairs.begin(), disabled_pairs.end());
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < static_cast<int>(links.size()); ++a) {
    if (links[a].collision.empty()) continue;
    for (int b = a + 1; b < static_cast<int>(links.size()); ++b) {
      if (links[b].collision.empty() || disabled.count({a, b})) continue;
      pairs.emplace_back(a, b);
    }
  }
  return pairs;
}

int RobotModel::deepest_common_link(int a, int b) const {
  // Parents come before their children: the later of the two is never the other's
  // ancestor, so it steps up.
  while (a != b) {
    int& later = a > b ? a : b;
    const int joint = links[later].parent_joint;
    if (joint < 0) return 0;  // a second root cannot be; the root holds everything
    later = joints[joint].parent_link;
  }
  return a;
}

std::vector<std::pair<int, int>> adjacent_link_pairs(const RobotModel& robot) {
  const int n = static_cast<int>(robot.links.size());
  std::vector<std::vector<int>> neighbours(n);
  std::set<std::pair<int, int>> pairs;
  for (const Joint& joint : robot.joints) {
    const int a = joint.parent_link, b = joint.child_link;
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
    pairs.emplace(std::min(a, b), std::max(a, b));
  }
  // From each link with geometry, walk the tree through links without geometry; the
  // first links with geometry met on the way are its adjacent ones.
  for (int from = 0; from < n; ++from) {
    if (robot.links[from].collision.empty()) continue;
    std::vector<int> stack = neighbours[from];
    std::vector<bool> seen(n, false);
    seen[from] = true;
    while (!stack.empty()) {
      const int at = stack.back();
      stack.pop_back();
      if (seen[at]) continue;
      seen[at] = true;
      if (!robot.links[at].collision.empty()) {
        pairs.emplace(std::min(from, at), std::max(from, at));
        continue;
      }
      for (const int next : neighbours[at])
        if (!seen[next]) stack.push_back(next);
    }
  }
  return {pairs.begin(), pairs.end()};
}

RobotModel make_rigid_robot(const std::string& name, TriangleMesh mesh,
                            const std::string& source_file) {
  RobotModel robot;
  robot.name = name;
  robot.source_file = source_file;
  Link body;
  body.name = name;
  body.solid = closed_triangles(mesh_components(mesh));
  body.collision = std::move(mesh);
  robot.links.push_back(std::move(body));
  return robot;
}

}  // namespace gplanner

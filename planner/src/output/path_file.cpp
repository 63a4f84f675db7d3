#include "gplanner/planner/output/path_file.h"

#include <iomanip>
#include <vector>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

void write_path_file(const std::string& path, const Scene& scene, const PlanResult& result,
                     const std::string& planner, const std::string& backend) {
  const ConfigurationSpace& space = scene.space;
  const RobotModel& robot = scene.robot;
  const int width = space.width();
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(9);
    // Every name taken from input is a YAML scalar that reads back as written
    // (yaml_scalar), in the comment too, where a newline would end it.
    out << "# A path from the start to the goal of " << yaml_scalar(scene.file)
        << ", by gplan plan.\n";
    out << "scene: " << yaml_scalar(scene.file) << "\n";
    out << "planner: " << yaml_scalar(planner) << "\n";
    out << "backend: " << yaml_scalar(backend) << "\n";
    out << "length: " << result.length << "  # under the planner's metric\n";
    out << "entries: [";
    for (int i = 0; i < width; ++i)
      out << (i ? ", " : "") << yaml_scalar(space.entry_name(robot, i));
    out << "]\n";
    // Rows are in the scene frame; the file gives what the scene file gives: world (or
    // plane) coordinates, summed in double. Far from the origin (the frame moved) nine
    // digits would not place them within the tolerance band: there, positions get all
    // of a double's.
    const bool moved = !scene.p_WS.isZero();
    auto position = [&](double v) -> std::ostream& {
      return out << std::setprecision(moved ? 17 : 9) << v << std::setprecision(9);
    };
    if (moved) {
      out << "# Positions in world coordinates; the planner's rows were relative to ["
          << scene.p_WS.x() << ", " << scene.p_WS.y() << ", " << scene.p_WS.z() << "].\n";
    }
    out << "waypoints:\n";
    std::vector<double> positions(robot.joints.size()), values(width);
    const std::size_t m = result.path.size() / width;
    for (std::size_t w = 0; w < m; ++w) {
      const float* q = &result.path[w * width];
      space.to_file_values(q, values.data());
      out << "  - configuration: [";
      for (int i = 0; i < width; ++i) {
        out << (i ? ", " : "");
        if (i < space.position_width()) {
          position(values[i]);
        } else {
          out << q[i];
        }
      }
      out << "]\n";
      const Eigen::Isometry3d X_WR = scene.X_WS() * space.base_pose(q);
      const Eigen::Quaterniond r(X_WR.linear());
      const Eigen::Vector3d t = X_WR.translation();
      out << "    base: {position: [";
      position(t.x()) << ", ";
      position(t.y()) << ", ";
      position(t.z()) << "], quat_wxyz: [" << r.w() << ", " << r.x() << ", " << r.y() << ", "
                      << r.z() << "]}\n";
      space.joint_positions(robot, q, positions.data());
      bool any = false;
      for (std::size_t j = 0; j < robot.joints.size(); ++j) {
        if (!robot.joints[j].is_single_dof()) continue;
        out << (any ? ", " : "    joints: {") << yaml_scalar(robot.joints[j].name) << ": "
            << positions[j];
        any = true;
      }
      if (any) out << "}\n";
    }
  });
}

}  // namespace gplanner

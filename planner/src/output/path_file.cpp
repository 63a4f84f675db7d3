#include "gplanner/planner/output/path_file.h"

#include <iomanip>
#include <vector>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/yaml_reader.h"
#include "gplanner/planner/scene/yaml_structure.h"

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

namespace {

// A path file is no larger than this (a million waypoints of a robot with tens of joints).
constexpr InputFileKind kPathFile{"path file", 1024 * kMiB};

YAML::Node load_path_file(const std::string& file, const YamlReader& in) {
  const YAML::Node root = load_checked_yaml(file, kPathFile, "");
  if (!root.IsMap() || !root["waypoints"] || !root["scene"])
    in.fail(root, "",
            "not a path file (gplan plan --out writes them): no scene and waypoints keys");
  return root;
}

}  // namespace

std::string path_file_scene(const std::string& file) {
  const YamlReader in(file);
  const YAML::Node root = load_path_file(file, in);
  return in.text(root["scene"], "scene");
}

std::vector<float> read_path_file(const std::string& file, const Scene& scene) {
  const YamlReader in(file);
  const YAML::Node root = load_path_file(file, in);
  const ConfigurationSpace& space = scene.space;
  const int width = space.width();
  const YAML::Node entries = in.required(root, "", "entries");
  if (!entries.IsSequence() || entries.size() != static_cast<std::size_t>(width)) {
    in.fail(entries, "entries",
            "expected the " + std::to_string(width) + " configuration entries of scene '" +
                scene.name + "', found " +
                std::to_string(entries.IsSequence() ? entries.size() : 0) +
                "; give the scene the path was planned in (--scene)");
  }
  for (int i = 0; i < width; ++i) {
    const std::string name = in.text(entries[i], "entries[" + std::to_string(i) + "]");
    if (name != space.entry_name(scene.robot, i)) {
      in.fail(entries[i], "entries[" + std::to_string(i) + "]",
              "'" + name + "' where scene '" + scene.name + "' has '" +
                  space.entry_name(scene.robot, i) +
                  "'; give the scene the path was planned in (--scene)");
    }
  }
  const YAML::Node waypoints = root["waypoints"];
  if (!waypoints.IsSequence() || waypoints.size() < 2)
    in.fail(waypoints, "waypoints", "expected a list of at least 2 waypoints");
  std::vector<float> path(waypoints.size() * width);
  std::vector<double> values;
  for (std::size_t w = 0; w < waypoints.size(); ++w) {
    const std::string key = "waypoints[" + std::to_string(w) + "]";
    if (!waypoints[w].IsMap()) in.fail(waypoints[w], key, "expected a map with a configuration");
    values = in.numbers(in.required(waypoints[w], key, "configuration"), key + ".configuration",
                        static_cast<std::size_t>(width));
    space.from_file_values(values.data(), &path[w * width]);
  }
  return path;
}

}  // namespace gplanner

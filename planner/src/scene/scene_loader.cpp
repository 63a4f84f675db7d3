#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "gplanner/planner/planning/motion_bound.h"  // the longest motion, for max_displacement
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/input_limits.h"
#include "gplanner/planner/scene/mesh_components.h"
#include "gplanner/planner/scene/mesh_loader.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "gplanner/planner/scene/urdf_loader.h"
#include "gplanner/planner/scene/yaml_reader.h"
#include "gplanner/planner/scene/yaml_structure.h"
#include "moveit_files.h"
#include "planner_settings_reader.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;

Eigen::Isometry3d read_pose(const YamlReader& in, const YAML::Node& node, const std::string& key) {
  in.expect_map(node, key, {"xyz", "quat_wxyz"});
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (node["xyz"]) X.translation() = in.vector3(node["xyz"], key + ".xyz");
  if (node["quat_wxyz"]) {
    X.linear() = in.quaternion(node["quat_wxyz"], key + ".quat_wxyz").toRotationMatrix();
  }
  return X;
}

void read_robot(const YamlReader& in, const YAML::Node& node, const MoveItRequest* request,
                Scene* scene) {
  const std::string key = "robot";
  in.expect_map(node, key,
                {"mesh", "urdf", "srdf", "packages", "base", "base_pose", "planned_joints",
                 "fixed_joints", "joint_limits"});
  ConfigurationSpace& space = scene->space;
  if (node["mesh"].IsDefined() == node["urdf"].IsDefined()) {
    in.fail(node, key, "give exactly one of mesh: (a rigid robot) or urdf: (an articulated one)");
  }
  if (node["mesh"]) {
    for (const char* name :
         {"srdf", "packages", "base_pose", "planned_joints", "fixed_joints", "joint_limits"}) {
      if (node[name]) in.fail(node[name], key + "." + name, "applies only to urdf: robots");
    }
    if (node["base"] && in.text(node["base"], key + ".base") != "floating") {
      in.fail(node["base"], key + ".base", "a mesh robot is a rigid body with a floating base");
    }
    const std::string mesh_path = in.path(node["mesh"], key + ".mesh", kMeshFile);
    TriangleMesh mesh = load_mesh(mesh_path, Eigen::Vector3d::Ones(),
                                  in.at(node["mesh"], key + ".mesh"), &scene->notices,
                                  &scene->input_files);
    scene->robot =
        make_rigid_robot(fs::path(mesh_path).stem().string(), std::move(mesh), mesh_path);
    space.base = BaseType::kFloating;
    return;
  }

  PackageMap packages;
  if (node["packages"]) {
    const YAML::Node map = node["packages"];
    if (!map.IsMap()) in.fail(map, key + ".packages", "expected a map of package name: folder");
    for (const auto& entry : map) {
      const std::string name = entry.first.as<std::string>();
      packages[name] = in.folder(entry.second, key + ".packages." + name);
    }
  }
  const std::string urdf_path = in.path(node["urdf"], key + ".urdf", kUrdfFile);
  scene->input_files.push_back(urdf_path);
  scene->robot =
      load_urdf(urdf_path, packages, in.at(node["urdf"], key + ".urdf"), &scene->notices);
  RobotModel& robot = scene->robot;
  scene->input_files.insert(scene->input_files.end(), robot.mesh_files.begin(),
                            robot.mesh_files.end());
  std::string srdf_path;
  if (node["srdf"]) {
    srdf_path = in.path(node["srdf"], key + ".srdf", kSrdfFile);
    scene->input_files.push_back(srdf_path);
    apply_srdf(&robot, srdf_path, in.at(node["srdf"], key + ".srdf"), &scene->notices);
  }

  const std::string base = node["base"] ? in.text(node["base"], key + ".base") : "fixed";
  if (base == "fixed") {
    space.base = BaseType::kFixed;
  } else if (base == "planar") {
    space.base = BaseType::kPlanar;
  } else if (base == "floating") {
    space.base = BaseType::kFloating;
  } else {
    in.fail(node["base"], key + ".base",
            "'" + base + "' is not a base; use fixed, planar or floating");
  }
  if (node["base_pose"]) {
    if (space.base == BaseType::kFloating) {
      in.fail(node["base_pose"], key + ".base_pose",
              "a floating base takes its pose from the configuration");
    }
    space.X_SB = read_pose(in, node["base_pose"], key + ".base_pose");  // S is W until moved
  }

  const std::size_t joint_count = robot.joints.size();
  space.fixed_positions.assign(joint_count, 0.0);
  for (std::size_t j = 0; j < joint_count; ++j) {
    const Joint& joint = robot.joints[j];
    if (joint.is_single_dof()) {
      space.fixed_positions[j] = std::min(std::max(0.0, joint.lower), joint.upper);
    }
  }

  auto single_dof_joint = [&](const YAML::Node& name_node, const std::string& where) {
    const std::string name = in.text(name_node, where);
    const int j = robot.find_joint(name);
    if (j < 0) in.fail(name_node, where, "URDF '" + urdf_path + "' has no joint '" + name + "'; use the name of one of its joints");
    if (!robot.joints[j].is_single_dof()) {
      in.fail(name_node, where,
              "joint '" + name + "' is " + joint_type_name(robot.joints[j].type) +
                  "; only revolute, continuous and prismatic joints take a value");
    }
    if (robot.joints[j].mimic_joint >= 0) {
      in.fail(name_node, where, "joint '" + name + "' mimics another joint and follows it");
    }
    return j;
  };

  if (node["planned_joints"]) {
    const YAML::Node list = node["planned_joints"];
    if (!list.IsSequence())
      in.fail(list, key + ".planned_joints", "expected a list of joint names");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = key + ".planned_joints[" + std::to_string(i) + "]";
      const int j = single_dof_joint(list[i], where);
      for (int planned : space.planned_joints) {
        if (planned == j) in.fail(list[i], where, "joint listed twice; remove the repeat");
      }
      space.planned_joints.push_back(j);
      space.lower.push_back(robot.joints[j].lower);
      space.upper.push_back(robot.joints[j].upper);
      space.continuous.push_back(robot.joints[j].type == JointType::kContinuous);
    }
  }
  if (!node["planned_joints"] && request != nullptr) {
    // The joints of the request's planning group, from the SRDF, as MoveIt plans them.
    if (srdf_path.empty()) {
      in.fail(node, key,
              "the motion plan request plans group '" + request->group +
                  "', which an SRDF defines: add srdf: (or list planned_joints)");
    }
    for (const int j :
         srdf_group_joints(robot, srdf_path, request->group, request->group_defined)) {
      space.planned_joints.push_back(j);
      space.lower.push_back(robot.joints[j].lower);
      space.upper.push_back(robot.joints[j].upper);
      space.continuous.push_back(robot.joints[j].type == JointType::kContinuous);
    }
  }
  if (space.planned_joints.empty() && space.base == BaseType::kFixed) {
    in.fail(node, key,
            "nothing to plan: list planned_joints or give the robot a planar or floating base");
  }
  auto planned_index = [&](int j) {
    for (std::size_t i = 0; i < space.planned_joints.size(); ++i) {
      if (space.planned_joints[i] == j) return static_cast<int>(i);
    }
    return -1;
  };

  if (node["fixed_joints"]) {
    const YAML::Node map = node["fixed_joints"];
    if (!map.IsMap()) in.fail(map, key + ".fixed_joints", "expected a map of joint name: value");
    for (const auto& entry : map) {
      const std::string where = key + ".fixed_joints." + entry.first.as<std::string>();
      const int j = single_dof_joint(entry.first, where);
      if (planned_index(j) >= 0)
        in.fail(entry.first, where, "joint is planned; it cannot also be fixed");
      const double value = in.number(entry.second, where);
      const Joint& joint = robot.joints[j];
      if (joint.type != JointType::kContinuous && (value < joint.lower || value > joint.upper)) {
        std::ostringstream problem;
        problem << value << " is outside the joint's limits [" << joint.lower << ", " << joint.upper
                << "]";
        in.fail(entry.second, where, problem.str());
      }
      space.fixed_positions[j] = value;
    }
  }

  if (node["joint_limits"]) {
    const YAML::Node map = node["joint_limits"];
    if (!map.IsMap())
      in.fail(map, key + ".joint_limits", "expected a map of joint name: [lower, upper]");
    for (const auto& entry : map) {
      const std::string where = key + ".joint_limits." + entry.first.as<std::string>();
      const int j = single_dof_joint(entry.first, where);
      const int i = planned_index(j);
      if (i < 0) in.fail(entry.first, where, "joint is not planned; list it in planned_joints");
      const std::vector<double> range = in.numbers(entry.second, where, 2);
      if (range[0] > range[1]) in.fail(entry.second, where, "inverted limits: lower exceeds upper");
      if (range[0] < space.lower[i] || range[1] > space.upper[i]) {
        std::ostringstream problem;
        problem << "may only narrow the URDF limits [" << space.lower[i] << ", " << space.upper[i]
                << "]";
        in.fail(entry.second, where, problem.str());
      }
      space.lower[i] = range[0];
      space.upper[i] = range[1];
      space.continuous[i] = false;  // narrowed: no longer wraps
    }
  }
}

void read_bounds(const YamlReader& in, const YAML::Node& node, ConfigurationSpace* space) {
  if (space->base == BaseType::kFixed) {
    if (node) in.fail(node, "bounds", "a fixed-base robot has no base bounds; remove bounds:");
    return;
  }
  if (!node)
    in.fail(node, "bounds", "missing: a moving base needs bounds: {min: [...], max: [...]}");
  in.expect_map(node, "bounds", {"min", "max"});
  const std::size_t count = space->base == BaseType::kFloating ? 3 : 2;
  const std::vector<double> lo =
      in.numbers(in.required(node, "bounds", "min"), "bounds.min", count);
  const std::vector<double> hi =
      in.numbers(in.required(node, "bounds", "max"), "bounds.max", count);
  for (std::size_t k = 0; k < count; ++k) {
    if (lo[k] >= hi[k]) {
      std::ostringstream problem;
      problem << "inverted or empty bounds on axis "
              << "xyz"[k] << ": min " << lo[k] << " is not below max " << hi[k]
              << "; swap or widen them";
      in.fail(node["min"], "bounds.min", problem.str());
    }
    space->base_min[k] = lo[k];
    space->base_max[k] = hi[k];
  }
}

// A start or goal as the file gives it (positions in world or plane coordinates), in
// double, checked against bounds and limits before anything is rounded.
std::vector<double> read_configuration(const YamlReader& in, const YAML::Node& node,
                                       const std::string& key, const Scene& scene) {
  const ConfigurationSpace& space = scene.space;
  const RobotModel& robot = scene.robot;
  in.expect_map(node, key, {"base", "joints"});
  std::vector<double> q(space.width(), 0.0);
  if (space.base == BaseType::kFixed) {
    if (node["base"])
      in.fail(node["base"], key + ".base", "a fixed-base robot takes no base pose here");
  } else {
    const YAML::Node base = in.required(node, key, "base");
    const std::string where = key + ".base";
    if (space.base == BaseType::kFloating) {
      in.expect_map(base, where, {"xyz", "quat_wxyz"});
      const Eigen::Vector3d p = in.vector3(in.required(base, where, "xyz"), where + ".xyz");
      const Eigen::Quaterniond r =
          in.quaternion(in.required(base, where, "quat_wxyz"), where + ".quat_wxyz");
      const double values[7] = {p.x(), p.y(), p.z(), r.w(), r.x(), r.y(), r.z()};
      for (int k = 0; k < 7; ++k) q[k] = values[k];
    } else {
      in.expect_map(base, where, {"xy", "theta"});
      const std::vector<double> xy = in.numbers(in.required(base, where, "xy"), where + ".xy", 2);
      q[0] = xy[0];
      q[1] = xy[1];
      q[2] = in.number(in.required(base, where, "theta"), where + ".theta");
    }
  }
  if (!space.planned_joints.empty()) {
    const YAML::Node joints = in.required(node, key, "joints");
    if (!joints.IsMap()) in.fail(joints, key + ".joints", "expected a map of joint name: value");
    std::set<std::string> planned;
    for (int j : space.planned_joints) planned.insert(robot.joints[j].name);
    for (const auto& entry : joints) {
      const std::string name = entry.first.as<std::string>();
      if (!planned.count(name)) {
        in.fail(entry.first, key + ".joints." + name,
                "not a planned joint; list it in robot.planned_joints or remove it");
      }
    }
    for (std::size_t i = 0; i < space.planned_joints.size(); ++i) {
      const std::string& name = robot.joints[space.planned_joints[i]].name;
      const YAML::Node value = in.required(joints, key + ".joints", name);
      q[space.base_width() + i] = in.number(value, key + ".joints." + name);
    }
  } else if (node["joints"]) {
    in.fail(node["joints"], key + ".joints", "the robot has no planned joints");
  }
  const std::string why = space.out_of_bounds_in_file_values(robot, q.data());
  if (!why.empty()) in.fail(node, key, why + "; move it inside or widen the bounds");
  return q;
}

// A mesh file loaded at one scale, with its components: loaded once however often the
// scene names it.
struct LoadedMesh {
  TriangleMesh mesh;
  MeshComponents components;
};
using MeshCache = std::map<std::pair<std::string, std::array<double, 3>>, LoadedMesh>;

void read_obstacles(const YamlReader& in, const YAML::Node& node, Scene* scene) {
  if (!node) return;
  if (!node.IsSequence()) in.fail(node, "obstacles", "expected a list of obstacles");
  if (node.size() > kMaxObstacles) {
    in.fail(node, "obstacles",
            "lists " + std::to_string(node.size()) + " obstacles, more than the " +
                std::to_string(kMaxObstacles) + " a scene may have; merge them into meshes");
  }
  std::set<std::string> noticed;  // files whose open components a notice named
  MeshCache meshes;
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node item = node[i];
    const std::string key = "obstacles[" + std::to_string(i) + "]";
    in.expect_map(item, key,
                  {"name", "mesh", "box", "sphere", "cylinder", "pose", "scale", "solid"});
    int shapes = 0;
    for (const char* shape : {"mesh", "box", "sphere", "cylinder"})
      shapes += item[shape].IsDefined();
    if (shapes != 1) in.fail(item, key, "give exactly one of mesh, box, sphere, cylinder");
    if (item["scale"] && !item["mesh"])
      in.fail(item["scale"], key + ".scale", "scale applies to meshes only");
    // solid: absent (closed components solid, open ones surfaces), true or false.
    int solid_key = -1;
    if (item["solid"]) {
      bool value = false;
      if (!item["solid"].IsScalar() || !YAML::convert<bool>::decode(item["solid"], value))
        in.fail(item["solid"], key + ".solid", "expected true or false");
      solid_key = value ? 1 : 0;
    }
    Obstacle obstacle;
    obstacle.defined = in.at(item, key);
    TriangleMesh mesh;
    if (item["mesh"]) {
      const std::string path = in.path(item["mesh"], key + ".mesh", kMeshFile);
      const Eigen::Vector3d scale =
          item["scale"] ? in.vector3(item["scale"], key + ".scale") : Eigen::Vector3d::Ones();
      if ((scale.array() == 0).any())
        in.fail(item["scale"], key + ".scale", "a zero scale flattens the mesh; give non-zero factors");
      const MeshCache::key_type cache_key{path, {scale.x(), scale.y(), scale.z()}};
      auto cached = meshes.find(cache_key);
      if (cached == meshes.end()) {
        LoadedMesh fresh;
        fresh.mesh = load_mesh(path, scale, in.at(item["mesh"], key + ".mesh"), &scene->notices,
                               &scene->input_files);
        fresh.components = mesh_components(fresh.mesh);
        cached = meshes.emplace(cache_key, std::move(fresh)).first;
      }
      const LoadedMesh& loaded = cached->second;
      mesh = loaded.mesh;
      obstacle.name = fs::path(path).stem().string();
      obstacle.file = path;
      if (solid_key == 0) {
        obstacle.solid.assign(mesh.triangle_count(), 0);
      } else {
        const MeshComponents& components = loaded.components;
        if (components.open_count > 0 && solid_key == 1) {
          in.fail(item["solid"], key + ".solid",
                  "mesh '" + path + "' is not closed: " + describe_open_components(components) +
                      "; repair it, or leave solid: out to make its closed components solid and "
                      "its open ones surfaces");
        }
        if (components.open_count > 0 && noticed.insert(path).second) {
          scene->notices.push_back(
              path + ": " + describe_open_components(components) +
              "; open components are surfaces (a robot wholly inside one is not in collision), "
              "closed ones solid; add solid: false to the obstacle to make it all a surface");
        }
        obstacle.solid = closed_triangles(components);
      }
    } else {
      if (item["box"]) {
        const Eigen::Vector3d size = in.vector3(item["box"], key + ".box");
        if ((size.array() <= 0).any())
          in.fail(item["box"], key + ".box", "side lengths must be positive");
        mesh = make_box(size);
        obstacle.name = "box";
        obstacle.shape = ObstacleShape::kBox;
        obstacle.dimensions = size;
      } else if (item["sphere"]) {
        const double radius = in.number(item["sphere"], key + ".sphere");
        if (radius <= 0) in.fail(item["sphere"], key + ".sphere", "the radius must be positive");
        mesh = make_sphere(radius);
        obstacle.name = "sphere";
        obstacle.shape = ObstacleShape::kSphere;
        obstacle.dimensions = Eigen::Vector3d(radius, 0, 0);
      } else {
        const YAML::Node c = item["cylinder"];
        in.expect_map(c, key + ".cylinder", {"radius", "length"});
        const double radius =
            in.number(in.required(c, key + ".cylinder", "radius"), key + ".cylinder.radius");
        const double length =
            in.number(in.required(c, key + ".cylinder", "length"), key + ".cylinder.length");
        if (radius <= 0 || length <= 0)
          in.fail(c, key + ".cylinder", "radius and length must be positive");
        mesh = make_cylinder(radius, length);
        obstacle.name = "cylinder";
        obstacle.shape = ObstacleShape::kCylinder;
        obstacle.dimensions = Eigen::Vector3d(radius, length, 0);
      }
      obstacle.solid.assign(mesh.triangle_count(), solid_key == 0 ? 0 : 1);
    }
    triangles += mesh.triangle_count();
    if (triangles > kMaxSceneTriangles) {
      in.fail(item, key,
              "brings the obstacles' triangles to " + std::to_string(triangles) +
                  ", more than the " + std::to_string(kMaxSceneTriangles) +
                  " a scene may have; simplify the meshes or place fewer");
    }
    if (item["name"]) obstacle.name = in.text(item["name"], key + ".name");
    const Eigen::Isometry3d X_WO =
        item["pose"] ? read_pose(in, item["pose"], key + ".pose") : Eigen::Isometry3d::Identity();
    obstacle.X_SO = X_WO;  // S is W until moved
    obstacle.mesh_S = transformed(mesh, X_WO);
    scene->obstacles.push_back(std::move(obstacle));
  }
}

// A notice naming the robot's links whose collision geometry has open components: those
// are surfaces (an obstacle wholly inside one is not seen).
void notice_open_links(Scene* scene) {
  const RobotModel& robot = scene->robot;
  std::string open;
  int count = 0;
  for (const Link& link : robot.links) {
    if (link.collision.empty()) continue;
    const std::vector<std::uint8_t> solid = link_solid_triangles(link);
    if (std::find(solid.begin(), solid.end(), 0) == solid.end()) continue;
    if (count < 8) open += std::string(count ? ", " : "") + link.name;
    ++count;
  }
  if (count == 0) return;
  if (count > 8) open += " and " + std::to_string(count - 8) + " more";
  scene->notices.push_back(robot.source_file + ": the collision geometry of " +
                           std::to_string(count) + " link" + (count == 1 ? "" : "s") + " (" + open +
                           ") is not closed; its open parts are surfaces (an obstacle wholly "
                           "inside one is not in collision), closed ones solid");
}

// Moves the scene frame to scene_frame_origin of the scene's world bounds: obstacles,
// bounds and base frame are made relative to it in double. A planar base's plane frame
// also moves within its plane, to the point nearest p_WS, so that x and y stay small.
void move_scene_frame(Scene* scene) {
  // S is W until moved. A fixed root counts too: the frame must suit the robot as well
  // as the obstacles (bounds_S, which sizes the band, leaves it out).
  Eigen::AlignedBox3d bounds_W = scene->bounds_S();
  bounds_W.extend(scene->space.base_region());
  const Eigen::Vector3d p_WS = scene_frame_origin(bounds_W);
  if (p_WS.isZero()) return;
  scene->p_WS = p_WS;
  for (Obstacle& obstacle : scene->obstacles) {
    for (Eigen::Vector3d& p : obstacle.mesh_S.vertices) p -= p_WS;
    obstacle.X_SO.translation() -= p_WS;
  }
  ConfigurationSpace& space = scene->space;
  const Eigen::Isometry3d X_SW(Eigen::Translation3d(-p_WS));
  if (space.base == BaseType::kFloating) {
    space.row_origin = p_WS;
  } else if (space.base == BaseType::kPlanar) {
    const Eigen::Isometry3d X_WB = space.X_SB;  // still the world's
    space.row_origin = X_WB.inverse() * p_WS;
    space.row_origin.z() = 0;
    space.X_SB = X_SW * X_WB * Eigen::Translation3d(space.row_origin);
  } else {
    space.X_SB = X_SW * space.X_SB;
  }
  space.base_min -= space.row_origin;
  space.base_max -= space.row_origin;
  std::ostringstream notice;
  notice << std::setprecision(12) << scene->file << ": the scene's centre lies "
         << bounds_W.center().norm() << " m from the world origin, more than its size ("
         << bounds_W.diagonal().norm() << " m): configuration rows (and roadmaps, OMPL states) "
         << "are relative to the world point [" << p_WS.x() << ", " << p_WS.y() << ", " << p_WS.z()
         << "]; path and check files give world coordinates";
  scene->notices.push_back(notice.str());
}

}  // namespace

Eigen::Vector3d scene_frame_origin(const Eigen::AlignedBox3d& bounds_W) {
  if (bounds_W.isEmpty()) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d c = bounds_W.center();
  const double d = bounds_W.diagonal().norm();
  if (!(c.norm() > d) || !(d > 0)) return Eigen::Vector3d::Zero();
  const double unit = std::pow(10.0, std::floor(std::log10(d)));
  return (c / unit).array().round() * unit;
}

bool Obstacle::is_solid_primitive() const {
  return shape != ObstacleShape::kMesh && !solid.empty() && solid[0] != 0;
}

bool Obstacle::is_solid_round_primitive() const {
  return is_solid_primitive() && shape != ObstacleShape::kBox;
}

Eigen::Isometry3d Scene::X_WS() const { return Eigen::Isometry3d(Eigen::Translation3d(p_WS)); }

std::size_t Scene::obstacle_triangle_count() const {
  std::size_t count = 0;
  for (const Obstacle& obstacle : obstacles) count += obstacle.mesh_S.triangle_count();
  return count;
}

TriangleMesh Scene::environment_mesh() const {
  TriangleMesh environment;
  for (const Obstacle& obstacle : obstacles) environment.append(obstacle.mesh_S);
  return environment;
}

Eigen::AlignedBox3d Scene::bounds_S() const {
  Eigen::AlignedBox3d box;
  for (const Obstacle& obstacle : obstacles) box.extend(obstacle.mesh_S.bounds());
  if (space.base != BaseType::kFixed) box.extend(space.base_region());
  return box;
}

// Joint values a MoveIt file gives (the planning scene's robot_state, then the
// request's start_state over it, as MoveIt applies a start state): joints not planned
// take them as their fixed values; planned joints' values are returned by name for the
// start. Names the URDF lacks are left out with one notice; joints that take no value
// (fixed ones) and mimic joints, which follow, are skipped.
std::map<std::string, MoveItJointValue> apply_moveit_joint_values(
    const std::vector<std::vector<MoveItJointValue>>& states, Scene* scene) {
  const RobotModel& robot = scene->robot;
  ConfigurationSpace& space = scene->space;
  // The last value given for each joint (the start state's over the scene's).
  std::map<std::string, MoveItJointValue> last;
  for (const std::vector<MoveItJointValue>& state : states)
    for (const MoveItJointValue& v : state) last[v.name] = v;
  std::map<std::string, MoveItJointValue> planned;
  std::set<std::string> unknown;
  for (const auto& [name, v] : last) {
    const int j = robot.find_joint(name);
    if (j < 0) {
      unknown.insert(name);
      continue;
    }
    const Joint& joint = robot.joints[j];
    if (!joint.is_single_dof() || joint.mimic_joint >= 0) continue;
    if (!std::isfinite(v.value))
      throw InputError(v.where, "joint '" + name + "': not a finite value");
    if (std::find(space.planned_joints.begin(), space.planned_joints.end(), j) !=
        space.planned_joints.end()) {
      planned[name] = v;
      continue;
    }
    if (joint.type != JointType::kContinuous && (v.value < joint.lower || v.value > joint.upper)) {
      std::ostringstream problem;
      problem << "joint '" << name << "' at " << v.value << " is outside its limits ["
              << joint.lower << ", " << joint.upper << "]; give a value within them";
      throw InputError(v.where, problem.str());
    }
    space.fixed_positions[j] = v.value;
  }
  if (!unknown.empty()) {
    std::string list;
    for (const std::string& name : unknown) list += (list.empty() ? "" : ", ") + name;
    scene->notices.push_back("joint states name joints URDF '" + robot.source_file +
                             "' does not have (" + list + "); their values are left out");
  }
  return planned;
}

// The request's start and goal as a scene file's start: and goal: nodes (joints by
// name), each value checked against its joint's limits where the request gives it.
std::pair<YAML::Node, YAML::Node> moveit_start_and_goal(
    const MoveItRequest& request, const std::string& request_path,
    const std::map<std::string, MoveItJointValue>& start_values, const Scene& scene) {
  const RobotModel& robot = scene.robot;
  const ConfigurationSpace& space = scene.space;
  if (space.base != BaseType::kFixed) {
    throw InputError({request_path, 0, "start_state"},
                     "a motion plan request gives joint values only; plan it with a fixed-base "
                     "robot (base: fixed)");
  }
  auto check = [&](const MoveItJointValue& v, int j) {
    const Joint& joint = robot.joints[j];
    if (!std::isfinite(v.value))
      throw InputError(v.where, "joint '" + v.name + "': not a finite value");
    if (joint.type != JointType::kContinuous && (v.value < joint.lower || v.value > joint.upper)) {
      std::ostringstream problem;
      problem << "joint '" << v.name << "' at " << v.value << " is outside its limits ["
              << joint.lower << ", " << joint.upper << "]; give a value within them";
      throw InputError(v.where, problem.str());
    }
  };
  std::string group_joints;
  for (const int j : space.planned_joints)
    group_joints += (group_joints.empty() ? "" : ", ") + robot.joints[j].name;
  YAML::Node start, goal;
  for (const int j : space.planned_joints) {
    const std::string& name = robot.joints[j].name;
    const auto found = start_values.find(name);
    if (found == start_values.end()) {
      throw InputError({request_path, 0, "start_state.joint_state"},
                       "gives no value for joint '" + name + "' of group '" + request.group +
                           "' (nor does the planning scene's robot_state); give it");
    }
    check(found->second, j);
    start["joints"][name] = found->second.value;
  }
  std::set<std::string> constrained;
  for (const MoveItJointValue& v : request.goal) {
    const int j = robot.find_joint(v.name);
    if (j < 0 || std::find(space.planned_joints.begin(), space.planned_joints.end(), j) ==
                     space.planned_joints.end()) {
      throw InputError(v.where, "constrains joint '" + v.name + "', which is not planned (group '" +
                                    request.group + "': " + group_joints +
                                    "); constrain the group's joints only");
    }
    if (!constrained.insert(v.name).second)
      throw InputError(v.where, "constrains joint '" + v.name + "' twice; give it once");
    check(v, j);
    goal["joints"][v.name] = v.value;
  }
  for (const int j : space.planned_joints) {
    if (!constrained.count(robot.joints[j].name)) {
      throw InputError({request_path, 0, "goal_constraints[0].joint_constraints"},
                       "leaves joint '" + robot.joints[j].name + "' of group '" + request.group +
                           "' free: gplanner plans to one configuration; constrain every joint "
                           "of the group");
    }
  }
  return {start, goal};
}

Scene load_scene(const std::string& path) {
  const YAML::Node root = load_checked_yaml(path, kSceneFile, "planner");
  const YamlReader in(path);
  Scene scene;
  scene.file = path;
  scene.input_files.push_back(path);
  try {
    in.expect_map(root, "",
                  {"name", "description", "narrowest_passage", "robot", "obstacles", "bounds",
                   "start", "goal", "planner", "moveit"});
    scene.name = root["name"] ? in.text(root["name"], "name") : fs::path(path).stem().string();
    if (root["description"]) scene.description = in.text(root["description"], "description");
    if (root["narrowest_passage"]) {
      scene.narrowest_passage = in.text(root["narrowest_passage"], "narrowest_passage");
    }
    // MoveIt's files (docs/scenes.md, "MoveIt files"): a planning scene's obstacles, a
    // motion plan request's group, start and goal.
    const YAML::Node moveit = root["moveit"];
    std::optional<MoveItRequest> request;
    std::string request_path, moveit_scene_path;
    if (moveit) {
      in.expect_map(moveit, "moveit", {"scene", "request"});
      if (moveit["request"]) {
        request_path = in.path(moveit["request"], "moveit.request", kMoveItRequestFile);
        scene.input_files.push_back(request_path);
        request = read_moveit_request(request_path);
        if (root["start"] || root["goal"]) {
          const YAML::Node given = root["start"] ? root["start"] : root["goal"];
          in.fail(given, root["start"] ? "start" : "goal",
                  "the start and goal come from moveit.request; remove start: and goal:");
        }
      }
      if (moveit["scene"]) {
        moveit_scene_path = in.path(moveit["scene"], "moveit.scene", kMoveItSceneFile);
        scene.input_files.push_back(moveit_scene_path);
      }
    }
    read_robot(in, in.required(root, "", "robot"), request ? &*request : nullptr, &scene);
    notice_open_links(&scene);
    read_bounds(in, root["bounds"], &scene.space);
    read_obstacles(in, root["obstacles"], &scene);
    std::vector<std::vector<MoveItJointValue>> joint_states;
    if (!moveit_scene_path.empty()) {
      joint_states.push_back(read_moveit_scene(moveit_scene_path, &scene));
      if (scene.obstacles.size() > kMaxObstacles) {
        in.fail(moveit["scene"], "moveit.scene",
                "brings the obstacles to " + std::to_string(scene.obstacles.size()) +
                    ", more than the " + std::to_string(kMaxObstacles) + " a scene may have");
      }
    }
    if (request) joint_states.push_back(request->start);
    const std::map<std::string, MoveItJointValue> start_values =
        apply_moveit_joint_values(joint_states, &scene);
    scene.dropped_obstacle_triangles = drop_unreachable_obstacle_triangles(&scene);
    move_scene_frame(&scene);
    YAML::Node start, goal;
    if (request) {
      std::tie(start, goal) = moveit_start_and_goal(*request, request_path, start_values, scene);
    } else {
      start = in.required(root, "", "start");
      goal = in.required(root, "", "goal");
    }
    for (auto [node, key, row] : {std::make_tuple(start, "start", &scene.start),
                                  std::make_tuple(goal, "goal", &scene.goal)}) {
      const std::vector<double> values = read_configuration(in, node, key, scene);
      row->resize(values.size());
      scene.space.from_file_values(values.data(), row->data());
    }
    if (request) {
      scene.start_defined = {request_path, 0, "start_state"};
      scene.goal_defined = {request_path, 0, "goal_constraints"};
    } else {
      scene.start_defined = in.at(start, "start");
      scene.goal_defined = in.at(goal, "goal");
    }
    scene.planner = read_planner_settings(in, root["planner"]);
    // The weights the space uses must not all be 0: every configuration would be at
    // distance 0 from every other (the roadmap, the k-NN and the edges' sampling).
    const PlannerSettings::DistanceWeights& w = scene.planner.distance_weights;
    const bool moving_base = scene.space.base != BaseType::kFixed;
    const bool joints = !scene.space.planned_joints.empty();
    if ((!moving_base || (w.position == 0 && w.rotation == 0)) && (!joints || w.joint == 0)) {
      const YAML::Node weights =
          root["planner"] ? root["planner"]["distance_weights"] : YAML::Node();
      in.fail(weights, "planner.distance_weights",
              std::string("the weights this robot's configurations use (") +
                  (moving_base ? "position, rotation" : "") + (moving_base && joints ? ", " : "") +
                  (joints ? "joint" : "") +
                  ") are all 0, so every configuration is at distance 0 from every other; "
                  "give at least one of them a positive weight");
    }
    refine_primitive_obstacles(&scene);
    check_band_representable(scene, in.at(root["robot"], "robot"), in.at(root["bounds"], "bounds"));
    // max_displacement: samples per edge by the robot's reach, as many as the longest
    // motion needs at most.
    const double max_displacement = scene.planner.max_displacement;
    const double longest = MotionBound(scene.robot, scene.space).longest_displacement();
    if (max_displacement > 0 && longest / max_displacement > kMaxEdgeSegments) {
      std::ostringstream what;
      what << "asks for up to " << std::setprecision(3) << longest / max_displacement
           << " samples per edge (the longest motion moves a robot point " << longest
           << " m), more than " << static_cast<long long>(kMaxEdgeSegments)
           << "; give at least " << longest / kMaxEdgeSegments << " m";
      in.fail(root["planner"]["max_displacement"], "planner.max_displacement", what.str());
    }
  } catch (const YAML::Exception& e) {
    // A value of the wrong shape where yaml-cpp itself converts (a map key, say).
    throw InputError({path, e.mark.line + 1, "yaml"}, e.msg + "; use plain text keys and values");
  }
  return scene;
}

}  // namespace gplanner

#include "moveit_files.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/input_limits.h"
#include "gplanner/planner/scene/triangle_mesh.h"
#include "gplanner/planner/scene/yaml_reader.h"
#include "gplanner/planner/scene/yaml_structure.h"

namespace gplanner {
namespace {

// The fields of the messages read, as ROS writes them to YAML; others are refused (a
// misspelt key would drop what it holds).
const std::set<std::string> kPlanningSceneKeys = {"name",
                                                  "robot_state",
                                                  "robot_model_name",
                                                  "fixed_frame_transforms",
                                                  "allowed_collision_matrix",
                                                  "link_padding",
                                                  "link_scale",
                                                  "object_colors",
                                                  "world",
                                                  "is_diff"};
const std::set<std::string> kCollisionObjectKeys = {
    "header",          "pose",           "id",         "type",   "primitives",
    "primitive_poses", "meshes",         "mesh_poses", "planes", "plane_poses",
    "subframe_names",  "subframe_poses", "operation"};

// A vector of three as ROS writes a Point or Vector3: [x, y, z] or {x:, y:, z:}.
Eigen::Vector3d read_xyz(const YamlReader& in, const YAML::Node& node, const std::string& key) {
  if (node.IsMap()) {
    in.expect_map(node, key, {"x", "y", "z"});
    return {in.number(in.required(node, key, "x"), key + ".x"),
            in.number(in.required(node, key, "y"), key + ".y"),
            in.number(in.required(node, key, "z"), key + ".z")};
  }
  return in.vector3(node, key);
}

// The rotation of the quaternion x y z w (w last), normalised, in *q; or, when it is of
// zero length or far from unit length, the problem, naming the parts as `parts` and the
// real part as `w`. MoveIt normalises what it is given, as do we, but one far from unit
// length is a mistake more often than a rotation: refuse it.
std::string unit_quaternion_xyzw(const double xyzw[4], const std::string& parts,
                                 const std::string& w, Eigen::Quaterniond* q) {
  double largest = 0;
  for (int k = 0; k < 4; ++k) largest = std::max(largest, std::abs(xyzw[k]));
  if (largest < 1e-9)
    return "zero-length quaternion; give " + parts + " with " + w + " = 1 for no rotation";
  // Scaled by the largest part first, so that tiny or huge parts do not under- or overflow.
  const Eigen::Quaterniond r(xyzw[3] / largest, xyzw[0] / largest, xyzw[1] / largest,
                             xyzw[2] / largest);
  const double norm = r.norm() * largest;
  if (std::abs(norm - 1) > 1e-3) {
    std::ostringstream problem;
    problem << "quaternion of length " << norm << ", not 1; give a unit quaternion " << parts;
    return problem.str();
  }
  *q = r.normalized();
  return "";
}

// A quaternion as ROS writes one: [x, y, z, w] or {x:, y:, z:, w:} (w last, unlike a
// gplanner scene's quat_wxyz).
Eigen::Quaterniond read_xyzw(const YamlReader& in, const YAML::Node& node, const std::string& key) {
  std::vector<double> v;
  if (node.IsMap()) {
    in.expect_map(node, key, {"x", "y", "z", "w"});
    for (const char* part : {"x", "y", "z", "w"})
      v.push_back(in.number(in.required(node, key, part), key + "." + part));
  } else {
    v = in.numbers(node, key, 4);
  }
  Eigen::Quaterniond q;
  const std::string problem = unit_quaternion_xyzw(v.data(), "[x, y, z, w]", "w", &q);
  if (!problem.empty()) in.fail(node, key, problem);
  return q;
}

// A geometry_msgs/Pose: {position:, orientation:}, either part absent meaning none.
Eigen::Isometry3d read_ros_pose(const YamlReader& in, const YAML::Node& node,
                                const std::string& key) {
  in.expect_map(node, key, {"position", "orientation"});
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (node["position"]) X.translation() = read_xyz(in, node["position"], key + ".position");
  if (node["orientation"])
    X.linear() = read_xyzw(in, node["orientation"], key + ".orientation").toRotationMatrix();
  return X;
}

// The frame an object is given in must be the world (or the robot's root, which a
// planning scene's fixed robot sits at): other frames are not resolved here.
void check_frame(const YamlReader& in, const YAML::Node& header, const std::string& key,
                 const Scene& scene) {
  if (!header) return;
  if (!header.IsMap()) in.fail(header, key, "expected a std_msgs/Header map");
  const YAML::Node frame = header["frame_id"];
  if (!frame) return;
  std::string id = in.text(frame, key + ".frame_id");
  if (!id.empty() && id[0] == '/') id = id.substr(1);
  const std::string root = scene.robot.links.empty() ? "" : scene.robot.links[0].name;
  const bool root_at_world = scene.space.base == BaseType::kFixed &&
                             scene.space.X_SB.isApprox(Eigen::Isometry3d::Identity());
  if (id.empty() || id == "world" || id == "map" || (id == root && root_at_world)) return;
  in.fail(frame, key + ".frame_id",
          "frame '" + id +
              "' is not resolved here: give the object in the world frame "
              "(frame_id: world, or the robot's root '" +
              root + "' where the robot sits at the origin)");
}

// One primitive of a collision object as an obstacle: MoveIt's SolidPrimitive (type by
// name or number, dimensions as shape_msgs defines them), placed at X_WP.
Obstacle primitive_obstacle(const YamlReader& in, const YAML::Node& node, const std::string& key,
                            const Eigen::Isometry3d& X_WP) {
  in.expect_map(node, key, {"type", "dimensions"});
  const YAML::Node type = in.required(node, key, "type");
  std::string name = in.text(type, key + ".type");
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::map<std::string, std::string> kNumbered = {
      {"1", "box"}, {"2", "sphere"}, {"3", "cylinder"}, {"4", "cone"}};
  if (kNumbered.count(name)) name = kNumbered.at(name);
  const YAML::Node dims = in.required(node, key, "dimensions");
  const std::string dims_key = key + ".dimensions";
  Obstacle obstacle;
  obstacle.defined = in.at(node, key);
  obstacle.X_SO = X_WP;  // S is W until moved
  TriangleMesh mesh;
  auto positive = [&](const std::vector<double>& values, const char* what) {
    for (const double v : values)
      if (!(v > 0)) in.fail(dims, dims_key, std::string(what) + " must be positive");
  };
  if (name == "box") {
    const std::vector<double> v = in.numbers(dims, dims_key, 3);
    positive(v, "a box's side lengths [x, y, z]");
    obstacle.shape = ObstacleShape::kBox;
    obstacle.dimensions = Eigen::Vector3d(v[0], v[1], v[2]);
    mesh = make_box(obstacle.dimensions);
  } else if (name == "sphere") {
    const std::vector<double> v = in.numbers(dims, dims_key, 1);
    positive(v, "a sphere's radius [r]");
    obstacle.shape = ObstacleShape::kSphere;
    obstacle.dimensions = Eigen::Vector3d(v[0], 0, 0);
    mesh = make_sphere(v[0]);
  } else if (name == "cylinder") {
    const std::vector<double> v = in.numbers(dims, dims_key, 2);  // height, radius
    positive(v, "a cylinder's [height, radius]");
    obstacle.shape = ObstacleShape::kCylinder;
    obstacle.dimensions = Eigen::Vector3d(v[1], v[0], 0);  // radius, length
    mesh = make_cylinder(v[1], v[0]);
  } else if (name == "cone") {
    in.fail(type, key + ".type",
            "cone primitives are not read yet; give the cone as a mesh (meshes: vertices and "
            "triangles)");
  } else {
    in.fail(type, key + ".type",
            "'" + name + "' is not a SolidPrimitive type; use box, sphere, cylinder (or 1, 2, 3)");
  }
  obstacle.name = name;
  obstacle.solid.assign(mesh.triangle_count(), 1);
  obstacle.mesh_S = transformed(mesh, X_WP);
  return obstacle;
}

// One shape_msgs/Mesh: vertices ([x, y, z] or {x:, y:, z:}) and triangles
// ({vertex_indices: [a, b, c]} or [a, b, c]), placed at X_WM; its closed components solid.
Obstacle mesh_obstacle(const YamlReader& in, const YAML::Node& node, const std::string& key,
                       const Eigen::Isometry3d& X_WM) {
  in.expect_map(node, key, {"vertices", "triangles"});
  const YAML::Node vertices = in.required(node, key, "vertices");
  const YAML::Node triangles = in.required(node, key, "triangles");
  if (!vertices.IsSequence()) in.fail(vertices, key + ".vertices", "expected a list of points");
  if (!triangles.IsSequence())
    in.fail(triangles, key + ".triangles", "expected a list of triangles");
  if (triangles.size() > kMaxMeshTriangles) {
    in.fail(triangles, key + ".triangles",
            "holds " + std::to_string(triangles.size()) + " triangles, more than the " +
                std::to_string(kMaxMeshTriangles) + " a mesh may have; simplify it");
  }
  TriangleMesh mesh;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    mesh.vertices.push_back(
        read_xyz(in, vertices[i], key + ".vertices[" + std::to_string(i) + "]"));
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const std::string where = key + ".triangles[" + std::to_string(i) + "]";
    YAML::Node t = triangles[i];
    if (t.IsMap()) {
      in.expect_map(t, where, {"vertex_indices"});
      t = in.required(t, where, "vertex_indices");
    }
    const std::vector<double> v = in.numbers(t, where, 3);
    Eigen::Vector3i corner;
    for (int k = 0; k < 3; ++k) {
      if (v[k] != std::floor(v[k]) || v[k] < 0 || v[k] >= double(vertices.size())) {
        in.fail(t, where,
                "vertex index " + std::to_string(v[k]) + " is not one of the mesh's " +
                    std::to_string(vertices.size()) + " vertices (0-based)");
      }
      corner(k) = static_cast<int>(v[k]);
    }
    mesh.triangles.push_back(corner);
  }
  if (mesh.triangles.empty())
    in.fail(triangles, key + ".triangles", "no triangle; give at least one");
  Obstacle obstacle;
  obstacle.name = "mesh";
  obstacle.defined = in.at(node, key);
  obstacle.X_SO = X_WM;
  obstacle.mesh_S = transformed(mesh, X_WM);  // solid left empty: decided from the mesh
  return obstacle;
}

void read_collision_objects(const YamlReader& in, const YAML::Node& world, Scene* scene) {
  if (!world) return;
  in.expect_map(world, "world", {"collision_objects", "octomap"});
  if (world["octomap"] && world["octomap"].IsMap() && world["octomap"]["octomap"] &&
      world["octomap"]["octomap"]["data"] && world["octomap"]["octomap"]["data"].size() > 0) {
    in.fail(world["octomap"], "world.octomap",
            "octomaps are not read; give the obstacles as objects");
  }
  const YAML::Node objects = world["collision_objects"];
  if (!objects) return;
  if (!objects.IsSequence())
    in.fail(objects, "world.collision_objects", "expected a list of collision objects");
  if (objects.size() > kMaxObstacles) {
    in.fail(objects, "world.collision_objects",
            "lists " + std::to_string(objects.size()) + " objects, more than the " +
                std::to_string(kMaxObstacles) + " a scene may have");
  }
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const YAML::Node object = objects[i];
    const std::string key = "world.collision_objects[" + std::to_string(i) + "]";
    in.expect_map(object, key, kCollisionObjectKeys);
    const std::string id = object["id"] ? in.text(object["id"], key + ".id") : "object";
    check_frame(in, object["header"], key + ".header", *scene);
    if (object["operation"]) {
      const std::string op = in.text(object["operation"], key + ".operation");
      if (op != "0" && op != "add" && op != "ADD")
        in.fail(object["operation"], key + ".operation",
                "only ADD (0) is read in a planning scene; give the objects as they stand");
    }
    if (object["planes"] && object["planes"].size() > 0)
      in.fail(object["planes"], key + ".planes", "planes (infinite) are not read; give a thin box");
    // The object's pose (since MoveIt 1.1): shapes are placed relative to it; without
    // one they are in the header's frame.
    const Eigen::Isometry3d X_WO = object["pose"] ? read_ros_pose(in, object["pose"], key + ".pose")
                                                  : Eigen::Isometry3d::Identity();
    for (const auto& [shapes_key, poses_key] :
         {std::pair<const char*, const char*>{"primitives", "primitive_poses"},
          {"meshes", "mesh_poses"}}) {
      const YAML::Node shapes = object[shapes_key];
      if (!shapes) continue;
      const YAML::Node poses = object[poses_key];
      if (!shapes.IsSequence()) in.fail(shapes, key + "." + shapes_key, "expected a list");
      if (!poses || !poses.IsSequence() || poses.size() != shapes.size()) {
        in.fail(poses ? poses : object, key + "." + poses_key,
                "give one pose per entry of " + std::string(shapes_key) + " (" +
                    std::to_string(shapes.size()) + ")");
      }
      for (std::size_t k = 0; k < shapes.size(); ++k) {
        const std::string index = "[" + std::to_string(k) + "]";
        const Eigen::Isometry3d X_WP =
            X_WO * read_ros_pose(in, poses[k], key + "." + poses_key + index);
        Obstacle obstacle =
            std::string(shapes_key) == "primitives"
                ? primitive_obstacle(in, shapes[k], key + "." + shapes_key + index, X_WP)
                : mesh_obstacle(in, shapes[k], key + "." + shapes_key + index, X_WP);
        obstacle.name = shapes.size() == 1 ? id : id + index;
        scene->obstacles.push_back(std::move(obstacle));
      }
    }
  }
}

// The allowed collision matrix: entry_names, and entry_values as a list of rows (each a
// list of booleans, or {enabled: [...]} as the message writes it).
void read_allowed_collisions(const YamlReader& in, const YAML::Node& acm, Scene* scene) {
  if (!acm) return;
  const std::string key = "allowed_collision_matrix";
  in.expect_map(acm, key,
                {"entry_names", "entry_values", "default_entry_names", "default_entry_values"});
  RobotModel& robot = scene->robot;
  std::vector<std::string> names;
  if (acm["entry_names"]) {
    const YAML::Node list = acm["entry_names"];
    if (!list.IsSequence()) in.fail(list, key + ".entry_names", "expected a list of names");
    for (std::size_t i = 0; i < list.size(); ++i)
      names.push_back(in.text(list[i], key + ".entry_names[" + std::to_string(i) + "]"));
  }
  const YAML::Node rows = acm["entry_values"];
  if (!names.empty() && (!rows || !rows.IsSequence() || rows.size() != names.size())) {
    in.fail(rows ? rows : acm, key + ".entry_values",
            "give one row per entry name (" + std::to_string(names.size()) + ")");
  }
  std::set<std::pair<int, int>> pairs(robot.disabled_pairs.begin(), robot.disabled_pairs.end());
  std::set<std::string> not_links;
  for (std::size_t r = 0; r < names.size(); ++r) {
    const std::string row_key = key + ".entry_values[" + std::to_string(r) + "]";
    YAML::Node row = rows[r];
    if (row.IsMap()) {
      in.expect_map(row, row_key, {"enabled"});
      row = in.required(row, row_key, "enabled");
    }
    if (!row.IsSequence() || row.size() != names.size())
      in.fail(row, row_key, "give one value per entry name (" + std::to_string(names.size()) + ")");
    for (std::size_t c = 0; c < names.size(); ++c) {
      bool allowed = false;
      if (!row[c].IsScalar() || !YAML::convert<bool>::decode(row[c], allowed))
        in.fail(row[c], row_key + "[" + std::to_string(c) + "]", "expected true or false");
      if (!allowed || r == c) continue;
      const int a = robot.find_link(names[r]), b = robot.find_link(names[c]);
      if (a < 0) not_links.insert(names[r]);
      if (b < 0) not_links.insert(names[c]);
      if (a >= 0 && b >= 0) pairs.emplace(std::min(a, b), std::max(a, b));
    }
  }
  robot.disabled_pairs.assign(pairs.begin(), pairs.end());
  if (!not_links.empty()) {
    std::string list;
    for (const std::string& name : not_links) list += (list.empty() ? "" : ", ") + name;
    scene->notices.push_back(in.file() + ": " + key + ": collisions allowed with " + list +
                             " (not links of the robot) are still checked: gplanner checks "
                             "the robot against every obstacle (conservative)");
  }
  if (acm["default_entry_values"] && acm["default_entry_values"].size() > 0) {
    scene->notices.push_back(in.file() + ": " + key +
                             ".default_entry_values: default allowed collisions are not "
                             "applied; those pairs are checked (conservative)");
  }
}

// robot_state.joint_state (names and positions), and a multi-DOF state that must be the
// identity (the base's pose is the scene file's robot.base_pose).
std::vector<MoveItJointValue> read_joint_state(const YamlReader& in, const YAML::Node& state,
                                               const std::string& key) {
  std::vector<MoveItJointValue> values;
  if (!state) return values;
  if (!state.IsMap()) in.fail(state, key, "expected a moveit_msgs/RobotState map");
  const YAML::Node joints = state["joint_state"];
  if (joints) {
    const std::string jkey = key + ".joint_state";
    if (!joints.IsMap()) in.fail(joints, jkey, "expected a sensor_msgs/JointState map");
    const YAML::Node names = joints["name"];
    const YAML::Node positions = joints["position"];
    if (names) {
      if (!names.IsSequence()) in.fail(names, jkey + ".name", "expected a list of joint names");
      if (!positions || !positions.IsSequence() || positions.size() != names.size()) {
        in.fail(positions ? positions : joints, jkey + ".position",
                "give one position per name (" + std::to_string(names.size()) + ")");
      }
      for (std::size_t i = 0; i < names.size(); ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        values.push_back({in.text(names[i], jkey + ".name" + index),
                          in.number(positions[i], jkey + ".position" + index),
                          in.at(positions[i], jkey + ".position" + index)});
      }
    }
  }
  const YAML::Node multi = state["multi_dof_joint_state"];
  if (multi && multi.IsMap() && multi["transforms"] && multi["transforms"].IsSequence()) {
    const YAML::Node transforms = multi["transforms"];
    for (std::size_t i = 0; i < transforms.size(); ++i) {
      const std::string tkey = key + ".multi_dof_joint_state.transforms[" + std::to_string(i) + "]";
      const YAML::Node t = transforms[i];
      in.expect_map(t, tkey, {"translation", "rotation"});
      const Eigen::Vector3d p = t["translation"]
                                    ? read_xyz(in, t["translation"], tkey + ".translation")
                                    : Eigen::Vector3d::Zero();
      const Eigen::Quaterniond q = t["rotation"] ? read_xyzw(in, t["rotation"], tkey + ".rotation")
                                                 : Eigen::Quaterniond::Identity();
      if (p.norm() > 1e-12 || q.angularDistance(Eigen::Quaterniond::Identity()) > 1e-12) {
        in.fail(t, tkey,
                "a base (virtual joint) away from the origin is not read here; give the "
                "robot's base pose in the scene file's robot.base_pose");
      }
    }
  }
  return values;
}

// MoveIt's .scene text (PlanningScene::saveGeometryToStream): a name line; per object
// "* ID", in the newer format its pose (x y z, then qx qy qz qw), its shape count, per
// shape its type and dimensions (box x y z, sphere r, cylinder r length, mesh V T then
// the vertices and triangles), its pose relative to the object's and a colour; in the
// newer format the subframes; "." ends the scene.
class SceneText {
 public:
  SceneText(std::string path, const std::string& text) : path_(std::move(path)) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
  }
  const std::string& path() const { return path_; }
  // The line of the next word (the last line at the end of the file).
  int line() {
    skip_space();
    return static_cast<int>(std::min(row_ + 1, std::max<std::size_t>(lines_.size(), 1)));
  }
  bool at_end() {
    skip_space();
    return row_ >= lines_.size();
  }
  // The next whitespace-separated word; an InputError naming `key` at the end of the file.
  std::string word(const std::string& key) {
    skip_space();
    if (row_ >= lines_.size())
      fail(key, "the file ends here, cut short; give the rest of the scene (export it again)");
    const std::string& text = lines_[row_];
    const std::size_t end = text.find_first_of(" \t\r", column_);
    const std::string w =
        text.substr(column_, end == std::string::npos ? std::string::npos : end - column_);
    column_ = end == std::string::npos ? text.size() : end;
    return w;
  }
  double number(const std::string& key) {
    const std::string w = word(key);
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (w.empty() || *end != '\0' || !std::isfinite(v))
      fail(key, "expected a finite number, found '" + w + "'");
    return v;
  }
  std::size_t count(const std::string& key, std::size_t most) {
    const std::string w = word(key);
    if (w.empty() || w.size() > 12 || w.find_first_not_of("0123456789") != std::string::npos ||
        std::stoull(w) > most)
      fail(key, "expected a count from 0 to " + std::to_string(most) + ", found '" + w + "'");
    return std::stoull(w);
  }
  // The rest of the current line, trimmed; the cursor moves to the next line.
  std::string rest_of_line() {
    std::string rest = row_ < lines_.size() ? lines_[row_].substr(column_) : "";
    const std::size_t first = rest.find_first_not_of(" \t\r");
    const std::size_t last = rest.find_last_not_of(" \t\r");
    ++row_;
    column_ = 0;
    return first == std::string::npos ? "" : rest.substr(first, last - first + 1);
  }
  // x y z qx qy qz qw, the quaternion checked as a YAML one is.
  Eigen::Isometry3d pose(const std::string& key) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    Eigen::Vector3d p;  // read in order: an argument list's order is unspecified
    for (int k = 0; k < 3; ++k) p[k] = number(key);
    X.translation() = p;
    const int at = line();
    double xyzw[4];
    for (double& part : xyzw) part = number(key);
    Eigen::Quaterniond q;
    const std::string problem = unit_quaternion_xyzw(xyzw, "qx qy qz qw", "qw", &q);
    if (!problem.empty()) throw InputError({path_, at, key}, problem);
    X.linear() = q.toRotationMatrix();
    return X;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) {
    throw InputError({path_, line(), key}, problem);
  }
  // The line after the first "* ID" line: it holds a pose (spaces) in the newer format.
  bool newer_format() const {
    for (std::size_t i = 0; i + 1 < lines_.size(); ++i) {
      if (!lines_[i].empty() && lines_[i][0] == '*') {
        const std::string& next = lines_[i + 1];
        const std::size_t first = next.find_first_not_of(" \t\r");
        const std::size_t last = next.find_last_not_of(" \t\r");
        return first != std::string::npos &&
               next.substr(first, last - first + 1).find(' ') != std::string::npos;
      }
    }
    return false;
  }

 private:
  void skip_space() {
    while (row_ < lines_.size()) {
      const std::size_t at = lines_[row_].find_first_not_of(" \t\r", column_);
      if (at != std::string::npos) {
        column_ = at;
        return;
      }
      ++row_;
      column_ = 0;
    }
  }
  std::string path_;
  std::vector<std::string> lines_;
  std::size_t row_ = 0, column_ = 0;
};

void read_scene_text(const std::string& path, Scene* scene) {
  SceneText in(path, read_input_file(path, kMoveItSceneFile, {path, 0, ""}));
  in.rest_of_line();  // the scene's name
  const bool newer = in.newer_format();
  std::size_t triangles = 0;
  while (true) {
    if (in.at_end())
      in.fail("end",
              "the file ends without the closing '.', cut short; give the rest of the scene "
              "(export it again)");
    const int marker_line = in.line();
    const std::string marker = in.word("object");
    if (marker == ".") return;
    if (marker != "*") {
      throw InputError({path, marker_line, "object"},
                       "expected '* OBJECT_ID' or the closing '.', found '" + marker + "'");
    }
    const std::string id = in.rest_of_line();
    const std::string key = "object '" + id + "'";
    const Eigen::Isometry3d X_WO = newer ? in.pose(key + " pose") : Eigen::Isometry3d::Identity();
    const std::size_t shapes = in.count(key + " shape count", 10000);
    for (std::size_t k = 0; k < shapes; ++k) {
      const std::string skey = key + " shape " + std::to_string(k);
      const int type_line = in.line();
      const std::string type = in.word(skey);
      Obstacle obstacle;
      TriangleMesh mesh;
      obstacle.defined = {path, type_line, skey};
      auto positive = [&](double v, const char* what) {
        if (!(v > 0))
          throw InputError({path, type_line, skey}, std::string(what) + " must be positive");
        return v;
      };
      if (type == "box") {
        obstacle.shape = ObstacleShape::kBox;
        for (int a = 0; a < 3; ++a)
          obstacle.dimensions[a] = positive(in.number(skey), "a box's side lengths");
        mesh = make_box(obstacle.dimensions);
      } else if (type == "sphere") {
        obstacle.shape = ObstacleShape::kSphere;
        obstacle.dimensions = Eigen::Vector3d(positive(in.number(skey), "a sphere's radius"), 0, 0);
        mesh = make_sphere(obstacle.dimensions.x());
      } else if (type == "cylinder") {  // radius, length
        obstacle.shape = ObstacleShape::kCylinder;
        const double radius = positive(in.number(skey), "a cylinder's radius");
        const double length = positive(in.number(skey), "a cylinder's length");
        obstacle.dimensions = Eigen::Vector3d(radius, length, 0);
        mesh = make_cylinder(radius, length);
      } else if (type == "mesh") {
        const std::size_t v = in.count(skey + " vertex count", 3 * kMaxMeshTriangles);
        const std::size_t t = in.count(skey + " triangle count", kMaxMeshTriangles);
        triangles += t;
        if (triangles > kMaxSceneTriangles)
          in.fail(skey, "brings the objects' triangles beyond the " +
                            std::to_string(kMaxSceneTriangles) + " a scene may have");
        for (std::size_t i = 0; i < v; ++i) {
          Eigen::Vector3d vertex;
          for (int k = 0; k < 3; ++k) vertex[k] = in.number(skey + " vertex");
          mesh.vertices.push_back(vertex);
        }
        for (std::size_t i = 0; i < t; ++i) {
          Eigen::Vector3i corner;
          for (int c = 0; c < 3; ++c) {
            const std::size_t index = in.count(skey + " triangle", ~std::size_t(0) >> 1);
            if (index >= v)
              in.fail(skey + " triangle", "vertex index " + std::to_string(index) +
                                              " is not one of the mesh's " + std::to_string(v) +
                                              " vertices (0-based)");
            corner(c) = static_cast<int>(index);
          }
          mesh.triangles.push_back(corner);
        }
        if (t == 0) in.fail(skey, "a mesh without a triangle; give at least one");
      } else if (type == "cone" || type == "plane") {
        throw InputError(
            {path, type_line, skey},
            type + " shapes are not read; give a cone as a mesh, a plane as a thin box");
      } else {
        throw InputError({path, type_line, skey},
                         "'" + type + "' is not a shape; use box, sphere, cylinder or mesh");
      }
      const Eigen::Isometry3d X_WP = X_WO * in.pose(skey + " pose");
      for (int c = 0; c < 4; ++c) in.number(skey + " colour");
      obstacle.name = shapes == 1 ? id : id + "[" + std::to_string(k) + "]";
      obstacle.X_SO = X_WP;  // S is W until moved
      if (obstacle.shape != ObstacleShape::kMesh) obstacle.solid.assign(mesh.triangle_count(), 1);
      obstacle.mesh_S = transformed(mesh, X_WP);
      scene->obstacles.push_back(std::move(obstacle));
      if (scene->obstacles.size() > kMaxObstacles)
        in.fail(skey,
                "more than the " + std::to_string(kMaxObstacles) + " obstacles a scene may have");
    }
    if (newer) {  // subframes: named poses on the object, nothing to check against
      const std::size_t subframes = in.count(key + " subframe count", 10000);
      for (std::size_t k = 0; k < subframes; ++k) {
        in.word(key + " subframe");
        in.pose(key + " subframe");
      }
    }
  }
}

}  // namespace

std::vector<MoveItJointValue> read_moveit_scene(const std::string& path, Scene* scene) {
  if (std::filesystem::path(path).extension() == ".scene") {
    read_scene_text(path, scene);
    return {};
  }
  const YAML::Node root = load_checked_yaml(path, kMoveItSceneFile, "");
  const YamlReader in(path);
  try {
    in.expect_map(root, "", kPlanningSceneKeys);
    read_collision_objects(in, root["world"], scene);
    read_allowed_collisions(in, root["allowed_collision_matrix"], scene);
    if (root["link_padding"] && root["link_padding"].size() > 0) {
      scene->notices.push_back(path +
                               ": link_padding is not applied: gplanner checks the "
                               "links as modelled, within its tolerance band");
    }
    return read_joint_state(in, root["robot_state"], "robot_state");
  } catch (const YAML::Exception& e) {
    throw InputError({path, e.mark.line + 1, "yaml"}, e.msg + "; use plain keys and values");
  }
}

MoveItRequest read_moveit_request(const std::string& path) {
  const YAML::Node root = load_checked_yaml(path, kMoveItRequestFile, "");
  const YamlReader in(path);
  MoveItRequest request;
  try {
    if (!root.IsMap()) in.fail(root, "", "expected a moveit_msgs/MotionPlanRequest map");
    const YAML::Node group = in.required(root, "", "group_name");
    request.group = in.text(group, "group_name");
    request.group_defined = in.at(group, "group_name");
    request.start = read_joint_state(in, root["start_state"], "start_state");
    const YAML::Node path_constraints = root["path_constraints"];
    if (path_constraints && path_constraints.IsMap()) {
      for (const char* kind : {"joint_constraints", "position_constraints",
                               "orientation_constraints", "visibility_constraints"}) {
        if (path_constraints[kind] && path_constraints[kind].size() > 0) {
          in.fail(path_constraints[kind], std::string("path_constraints.") + kind,
                  "path constraints are not honoured by gplanner's planners; leave them out");
        }
      }
    }
    const YAML::Node goals = in.required(root, "", "goal_constraints");
    if (!goals.IsSequence() || goals.size() != 1) {
      in.fail(
          goals, "goal_constraints",
          "give exactly one goal (a list of one Constraints); gplanner plans to one joint goal");
    }
    const YAML::Node goal = goals[0];
    const std::string gkey = "goal_constraints[0]";
    if (!goal.IsMap()) in.fail(goal, gkey, "expected a moveit_msgs/Constraints map");
    for (const char* kind :
         {"position_constraints", "orientation_constraints", "visibility_constraints"}) {
      if (goal[kind] && goal[kind].size() > 0) {
        in.fail(goal[kind], gkey + "." + kind,
                "not a joint goal: gplanner plans to joint goals; give joint_constraints for "
                "every joint of the group (solve the pose for them first)");
      }
    }
    const YAML::Node joints = goal["joint_constraints"];
    if (!joints || !joints.IsSequence() || joints.size() == 0) {
      in.fail(joints ? joints : goal, gkey + ".joint_constraints",
              "no joint constraints: give the goal's value of every joint of the group");
    }
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const std::string jkey = gkey + ".joint_constraints[" + std::to_string(i) + "]";
      const YAML::Node c = joints[i];
      in.expect_map(c, jkey,
                    {"joint_name", "position", "tolerance_above", "tolerance_below", "weight"});
      const YAML::Node position = in.required(c, jkey, "position");
      request.goal.push_back({in.text(in.required(c, jkey, "joint_name"), jkey + ".joint_name"),
                              in.number(position, jkey + ".position"),
                              in.at(position, jkey + ".position")});
    }
  } catch (const YAML::Exception& e) {
    throw InputError({path, e.mark.line + 1, "yaml"}, e.msg + "; use plain keys and values");
  }
  return request;
}

}  // namespace gplanner

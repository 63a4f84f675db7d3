#include "fuzz/fuzz_targets.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "command_line.h"
#include "gplan_commands.h"
#include "gplanner/collision_gpu/bvh.h"
#include "gplanner/planner/output/roadmap_file.h"
#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/mesh_loader.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/urdf_loader.h"

namespace gplanner::fuzz {
namespace {

namespace fs = std::filesystem;

const char* const kBoxObj =
    "v -0.1 -0.1 -0.1\nv 0.1 -0.1 -0.1\nv 0.1 0.1 -0.1\nv -0.1 0.1 -0.1\n"
    "v -0.1 -0.1 0.1\nv 0.1 -0.1 0.1\nv 0.1 0.1 0.1\nv -0.1 0.1 0.1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

const char* const kArmUrdf = R"(<robot name="arm">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><collision><geometry><mesh filename="box.obj"/></geometry></collision></link>
  <link name="lower"><collision><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="continuous"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/></joint>
</robot>
)";

const char* const kSceneYaml = R"(name: tiny
robot:
  mesh: box.obj
obstacles:
  - box: [0.2, 2.0, 2.0]
    pose: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}
bounds:
  min: [-1, -1.5, -1]
  max: [1, 1.5, 1]
start:
  base: {xyz: [-0.6, 0, 0], quat_wxyz: [1, 0, 0, 0]}
goal:
  base: {xyz: [0.6, 0, 0], quat_wxyz: [1, 0, 0, 0]}
planner:
  roadmap: {milestones: 50}
)";

const char* const kArmYaml = R"(name: arm
robot:
  urdf: arm.urdf
  planned_joints: [shoulder, elbow]
obstacles:
  - box: [0.2, 0.2, 0.2]
    pose: {xyz: [0, 0, 1.5]}
start:
  joints: {shoulder: -0.5, elbow: 0.5}
goal:
  joints: {shoulder: 0.5, elbow: -0.5}
planner:
  roadmap: {milestones: 50}
)";

// One folder per process holding the fixtures, and the input written beside them;
// removed at exit (the name is never destroyed, so that the exit handler can use it).
const std::string& folder() {
  static const std::string* const path = [] {
    const fs::path p = fs::temp_directory_path() / ("gplanner_fuzz_" + std::to_string(getpid()));
    fs::create_directories(p);
    std::ofstream(p / "box.obj") << kBoxObj;
    std::ofstream(p / "arm.urdf") << kArmUrdf;
    std::ofstream(p / "scene.yaml") << kSceneYaml;
    std::ofstream(p / "arm.yaml") << kArmYaml;
    return new std::string(p.string());
  }();
  static const bool cleanup = std::atexit([] {
                                std::error_code ignored;
                                fs::remove_all(*path, ignored);
                              }) == 0;
  (void)cleanup;
  return *path;
}

std::string write(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = folder() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
  std::abort();
}

// Every refusal is one line of a few hundred characters (input_error.h), however long or
// strange the input it echoes.
void check_message(const InputError& error) {
  const std::string message = error.what();
  if (message.find('\n') != std::string::npos || message.find('\x1b') != std::string::npos) {
    finding("an input error's message holds a line break or a terminal escape");
  }
  if (message.size() > 1000) finding("an input error's message is longer than 1000 characters");
}

// The small scene's fixtures (the command line may have written over them).
void restore_fixtures() {
  const fs::path p = folder();
  std::ofstream(p / "box.obj") << kBoxObj;
  std::ofstream(p / "arm.urdf") << kArmUrdf;
  std::ofstream(p / "scene.yaml") << kSceneYaml;
  std::ofstream(p / "arm.yaml") << kArmYaml;
}

const Scene& small_scene() {
  static const Scene* const scene = new Scene(load_scene(folder() + "/scene.yaml"));
  return *scene;
}

// A valid roadmap for the small scene: start, goal and a vertex between, two edges.
void write_valid_roadmap(const std::string& path) {
  const Scene& scene = small_scene();
  Roadmap roadmap(scene.space.width());
  roadmap.add_vertex(scene.start.data());
  roadmap.add_vertex(scene.goal.data());
  std::vector<float> middle(scene.start.begin(), scene.start.end());
  middle[1] = 1.2f;  // y: beside the wall
  roadmap.add_vertex(middle.data());
  roadmap.add_edge(0, 2, 1.0f);
  roadmap.add_edge(1, 2, 1.0f);
  save_roadmap(roadmap, scene, path);
}

// Whether `word` is an unsigned integer of at most twelve digits above `cap` (an
// in-range count that would only make the run slow).
bool slow_count(const std::string& word, unsigned long long cap) {
  if (word.empty() || word.size() > 12) return false;
  for (const char c : word)
    if (c < '0' || c > '9') return false;
  return std::stoull(word) > cap;
}

// Swallows what gplan prints while the command line target runs.
class Silence {
 public:
  Silence() : out_(std::cout.rdbuf(nullptr)), err_(std::cerr.rdbuf(nullptr)) {}
  ~Silence() {
    std::cout.rdbuf(out_);
    std::cerr.rdbuf(err_);
    std::cout.clear();
    std::cerr.clear();
  }

 private:
  std::streambuf* out_;
  std::streambuf* err_;
};

std::uint64_t fnv1a(const std::uint8_t* data, std::size_t size) {
  std::uint64_t value = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) {
    value ^= data[i];
    value *= 1099511628211ull;
  }
  return value;
}

}  // namespace

void scene_file(const std::uint8_t* data, std::size_t size) {
  const std::string path = write("scene.yaml", data, size);
  try {
    const Scene scene = load_scene(path);
    if (static_cast<int>(scene.start.size()) != scene.space.width() ||
        static_cast<int>(scene.goal.size()) != scene.space.width()) {
      finding("a loaded scene's start or goal does not fit its configuration width");
    }
  } catch (const InputError& e) {
    check_message(e);
  }
}

void urdf_file(const std::uint8_t* data, std::size_t size) {
  const std::string path = write("robot.urdf", data, size);
  try {
    const RobotModel robot = load_urdf(path, {}, {"fuzz.yaml", 1, "robot.urdf"});
    // Parents before children, every joint joining existing links.
    for (std::size_t l = 1; l < robot.links.size(); ++l) {
      const int j = robot.links[l].parent_joint;
      if (j < 0 || j >= static_cast<int>(robot.joints.size()) ||
          robot.joints[j].parent_link >= static_cast<int>(l)) {
        finding("a loaded URDF's links are not in topological order");
      }
    }
  } catch (const InputError& e) {
    check_message(e);
  }
}

void srdf_file(const std::uint8_t* data, std::size_t size) {
  static const RobotModel arm = load_urdf(folder() + "/arm.urdf", {}, {"fuzz.yaml", 1, "arm"});
  const std::string path = write("robot.srdf", data, size);
  RobotModel robot = arm;
  std::vector<std::string> notices;
  try {
    apply_srdf(&robot, path, {"fuzz.yaml", 1, "srdf"}, &notices);
    for (const auto& [a, b] : robot.disabled_pairs) {
      if (a < 0 || b < 0 || a >= static_cast<int>(robot.links.size()) ||
          b >= static_cast<int>(robot.links.size())) {
        finding("an SRDF pair names a link out of range");
      }
    }
  } catch (const InputError& e) {
    check_message(e);
  }
}

void triangle_soup(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return;
  const std::size_t vertices = std::min<std::size_t>(data[0] | (data[1] << 8), 4096);
  std::size_t at = 2;
  TriangleMesh mesh;
  for (std::size_t v = 0; v < vertices && at + 12 <= size; ++v, at += 12) {
    float xyz[3];
    std::memcpy(xyz, data + at, 12);
    mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  for (; at + 12 <= size; at += 12) {
    std::int32_t t[3];
    std::memcpy(t, data + at, 12);
    mesh.triangles.emplace_back(t[0], t[1], t[2]);
  }
  try {
    validate_mesh(&mesh, {"fuzz.obj", 0, ""}, "triangle soup");
  } catch (const InputError&) {
    return;
  }
  std::vector<double> xyz;
  for (const Eigen::Vector3d& p : mesh.vertices) xyz.insert(xyz.end(), p.data(), p.data() + 3);
  std::vector<int> indices;
  for (const Eigen::Vector3i& t : mesh.triangles)
    indices.insert(indices.end(), t.data(), t.data() + 3);
  const Bvh bvh = build_bvh(xyz.data(), static_cast<int>(mesh.vertices.size()), indices.data(),
                            static_cast<int>(mesh.triangles.size()));
  if (bvh.triangles.size() != mesh.triangles.size())
    finding("the BVH holds a different number of triangles than the mesh");
  std::vector<int> seen(bvh.triangles.size(), 0);
  for (const BvhNode& node : bvh.nodes) {
    if (!node.is_leaf()) continue;
    const int t = node.triangle();
    if (t < 0 || t >= static_cast<int>(seen.size())) finding("a leaf names no triangle");
    ++seen[t];
    // The leaf's box holds its triangle (up to float rounding of the box itself).
    const geometry::Obb<float> box = node_box(node);
    for (int k = 0; k < 3; ++k) {
      const geometry::Vec3<float> p{bvh.triangles[t].v[k][0], bvh.triangles[t].v[k][1],
                                    bvh.triangles[t].v[k][2]};
      const geometry::Vec3<float> d = transpose(box.axes) * (p - box.center);
      const float e[3] = {box.extent.x, box.extent.y, box.extent.z};
      const float dd[3] = {d.x, d.y, d.z};
      for (int a = 0; a < 3; ++a) {
        const float scale =
            std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), e[a], 1e-30f});
        if (std::fabs(dd[a]) > e[a] + 1e-5f * scale) finding("a leaf's box misses its triangle");
      }
    }
  }
  for (const int count : seen)
    if (count != 1) finding("a triangle is in no leaf or in several");
  // An inner node's split parts its children: the first child's triangle centroids lie
  // at or below it along the node's first axis, the second child's at or above
  // (subtree_extremes: the least and greatest centroid of subtree n along that axis).
  auto subtree_extremes = [&](auto&& self, int n, const BvhNode& along) -> std::pair<float, float> {
    const BvhNode& node = bvh.nodes[n];
    if (node.is_leaf()) {
      const BvhTriangle& t = bvh.triangles[node.triangle()];
      float c = 0;
      for (int k = 0; k < 3; ++k)
        c += along.axes[0] * t.v[k][0] + along.axes[3] * t.v[k][1] + along.axes[6] * t.v[k][2];
      return {c / 3, c / 3};
    }
    const auto a = self(self, node.child, along), b = self(self, node.child + 1, along);
    return {std::min(a.first, b.first), std::max(a.second, b.second)};
  };
  float largest = 1e-30f;  // largest coordinate: the projections' float rounding scales with it
  for (const BvhTriangle& t : bvh.triangles)
    for (int k = 0; k < 3; ++k)
      largest =
          std::max({largest, std::fabs(t.v[k][0]), std::fabs(t.v[k][1]), std::fabs(t.v[k][2])});
  for (const BvhNode& node : bvh.nodes) {
    if (node.is_leaf()) continue;
    const auto below = subtree_extremes(subtree_extremes, node.child, node);
    const auto above = subtree_extremes(subtree_extremes, node.child + 1, node);
    if (below.second > node.split + 1e-5f * largest || above.first < node.split - 1e-5f * largest)
      finding("an inner node's split does not part its children");
  }
}

void command_line(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words;
  if (size > 0) {
    words.emplace_back();
    for (std::size_t i = 0; i < size; ++i) {
      if (data[i] == 0) {
        words.emplace_back();
      } else {
        words.back() += static_cast<char>(data[i]);
      }
    }
  }
  const std::map<std::string, unsigned long long> caps = {
      {"n", 1000}, {"repeat", 3}, {"milestones", 1000}, {"threads", 64}};
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (word.find('/') != std::string::npos) return;
    if (word.rfind("--time-limit", 0) == 0) return;
    for (const auto& [option, cap] : caps) {
      const std::string flag = "--" + option;
      if (word == flag && i + 1 < words.size() && slow_count(words[i + 1], cap)) return;
      if (word.rfind(flag + "=", 0) == 0 && slow_count(word.substr(flag.size() + 1), cap)) return;
    }
  }
  // `gplan bench` runs the program gplan-bench in gplan's place: not in this process.
  if (!words.empty() && words[0] == "bench") return;
  if (!words.empty() && words[0] == "plan") {
    words.push_back("--time-limit");
    words.push_back("0.05");
  }
  std::vector<char*> argv;
  std::string program = "gplan";
  argv.push_back(program.data());
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);

  restore_fixtures();
  write_valid_roadmap(folder() + "/map.roadmap");
  const fs::path working = fs::current_path();
  fs::current_path(folder());
  std::string unexpected;
  {
    // GPLANNER_FUZZ_VERBOSE=1 shows what gplan prints (when reproducing a finding).
    const char* verbose = std::getenv("GPLANNER_FUZZ_VERBOSE");
    std::unique_ptr<Silence> silence;
    if (!(verbose && *verbose == '1')) silence = std::make_unique<Silence>();
    try {
      gplan::run_command(static_cast<int>(argv.size()) - 1, argv.data());
    } catch (const gplan::UsageError& e) {
      if (!silence) std::cerr << "usage error: " << e.what() << "\n";
    } catch (const InputError& e) {
      if (!silence) std::cerr << "input error: " << e.what() << "\n";
      check_message(e);
    } catch (const std::exception& e) {
      unexpected = e.what();
    }
  }
  fs::current_path(working);
  // Whatever the run wrote goes, so that the next input starts from the fixtures.
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(folder(), ignored)) {
    const std::string name = entry.path().filename().string();
    if (name != "box.obj" && name != "arm.urdf" && name != "scene.yaml" && name != "arm.yaml")
      fs::remove_all(entry.path(), ignored);
  }
  if (!unexpected.empty()) finding("gplan threw other than a usage or input error: " + unexpected);
}

void roadmap_file(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const Scene& scene = small_scene();
  std::vector<std::uint8_t> bytes(data + 1, data + size);
  if ((data[0] & 1) && bytes.size() >= 8) {
    const std::uint64_t sum = fnv1a(bytes.data(), bytes.size() - 8);
    std::memcpy(&bytes[bytes.size() - 8], &sum, 8);
  }
  const std::string path = write("fuzz.roadmap", bytes.data(), bytes.size());
  Roadmap roadmap;
  try {
    roadmap = load_roadmap(scene, path);
  } catch (const InputError& e) {
    check_message(e);
    return;
  }
  const int width = scene.space.width();
  if (roadmap.width() != width) finding("a loaded roadmap's width is not the scene's");
  if (roadmap.vertices().size() != roadmap.vertex_count() * width)
    finding("a loaded roadmap's vertex array does not hold its vertices");
  for (std::size_t v = 0; v < roadmap.vertex_count(); ++v) {
    const float* q = roadmap.vertex(v);
    for (int k = 0; k < width; ++k)
      if (!std::isfinite(q[k])) finding("a loaded roadmap vertex is not finite");
    const std::string outside = scene.space.out_of_bounds(scene.robot, q);
    if (!outside.empty()) finding("a loaded roadmap vertex is out of bounds: " + outside);
  }
  for (const RoadmapEdge& e : roadmap.edges()) {
    if (e.a == e.b || e.a >= roadmap.vertex_count() || e.b >= roadmap.vertex_count())
      finding("a loaded roadmap edge does not join two distinct existing vertices");
    if (!std::isfinite(e.length) || e.length < 0)
      finding("a loaded roadmap edge length is not finite and non-negative");
    if (static_cast<int>(e.state) > 2) finding("a loaded roadmap edge state is unknown");
  }
}

}  // namespace gplanner::fuzz

#include "fuzz/fuzz_targets.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/bvh.h"
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

// One folder per process holding the fixtures, and the input written beside them;
// removed at exit (the name is never destroyed, so that the exit handler can use it).
const std::string& folder() {
  static const std::string* const path = [] {
    const fs::path p = fs::temp_directory_path() / ("gplanner_fuzz_" + std::to_string(getpid()));
    fs::create_directories(p);
    std::ofstream(p / "box.obj") << kBoxObj;
    std::ofstream(p / "arm.urdf") << kArmUrdf;
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

}  // namespace gplanner::fuzz

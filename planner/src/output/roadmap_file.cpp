#include "gplanner/planner/output/roadmap_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/input_file.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {
namespace {

constexpr char kMagic[] = "gplanner-roadmap 1\n";
constexpr std::size_t kMagicBytes = sizeof(kMagic) - 1;
// After the magic: the scene's fingerprint, the width, the vertex and edge counts.
constexpr std::size_t kHeaderBytes = kMagicBytes + 8 + 4 + 8 + 8;
constexpr std::size_t kEdgeBytes = 4 + 4 + 4 + 1;
constexpr std::size_t kChecksumBytes = 8;
constexpr char kTruncated[] = "roadmap file is damaged (truncated); build it again";

// FNV-1a, 64 bit.
class Hash {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      value_ ^= p[i];
      value_ *= 1099511628211ull;
    }
  }
  template <typename T>
  void add(const T& x) {
    bytes(&x, sizeof(x));
  }
  void add(const std::string& s) {
    add(s.size());
    bytes(s.data(), s.size());
  }
  void add(const Eigen::Isometry3d& X) { bytes(X.matrix().data(), sizeof(double) * 16); }
  void add(const TriangleMesh& mesh) {
    add(mesh.vertices.size());
    for (const Eigen::Vector3d& v : mesh.vertices) bytes(v.data(), sizeof(double) * 3);
    add(mesh.triangles.size());
    for (const auto& t : mesh.triangles) bytes(t.data(), sizeof(int) * 3);
  }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 1469598103934665603ull;
};

template <typename T>
void put(std::ostream& out, const T& x) {
  out.write(reinterpret_cast<const char*>(&x), sizeof(T));
}

// Reads from an in-memory image, failing with the file's name when it runs short.
class Reader {
 public:
  Reader(const std::string& data, const std::string& path) : data_(data), path_(path) {}
  template <typename T>
  T get() {
    T x;
    take(&x, sizeof(T));
    return x;
  }
  void take(void* out, std::size_t n) {
    if (n > data_.size() - at_) throw InputError({path_, 0, ""}, kTruncated);
    std::memcpy(out, data_.data() + at_, n);
    at_ += n;
  }
  std::size_t at() const { return at_; }

 private:
  const std::string& data_;
  const std::string& path_;
  std::size_t at_ = 0;
};

}  // namespace

std::uint64_t scene_fingerprint(const Scene& scene) {
  Hash h;
  const RobotModel& robot = scene.robot;
  h.add(robot.links.size());
  for (const Link& link : robot.links) {
    h.add(link.parent_joint);
    h.add(link.collision);
  }
  h.add(robot.joints.size());
  for (const Joint& joint : robot.joints) {
    h.add(static_cast<int>(joint.type));
    h.add(joint.parent_link);
    h.add(joint.child_link);
    h.add(joint.X_PJ);
    h.bytes(joint.axis_J.data(), sizeof(double) * 3);
    h.add(joint.lower);
    h.add(joint.upper);
    h.add(joint.mimic_joint);
    h.add(joint.mimic_multiplier);
    h.add(joint.mimic_offset);
  }
  for (const auto& [a, b] : robot.disabled_pairs) {
    h.add(a);
    h.add(b);
  }
  h.add(scene.obstacles.size());
  for (const Obstacle& obstacle : scene.obstacles) h.add(obstacle.mesh_S);
  const ConfigurationSpace& space = scene.space;
  h.add(static_cast<int>(space.base));
  h.add(space.X_SB);
  h.bytes(space.base_min.data(), sizeof(double) * 3);
  h.bytes(space.base_max.data(), sizeof(double) * 3);
  // Rows are in the scene frame: they mean the same world poses only with the same
  // frame. Hashed only when moved, so that roadmaps of scenes near the origin (whose
  // frame is the world's) keep their fingerprint.
  if (!scene.p_WS.isZero()) {
    h.bytes(scene.p_WS.data(), sizeof(double) * 3);
    h.bytes(space.row_origin.data(), sizeof(double) * 3);
  }
  for (std::size_t j = 0; j < space.planned_joints.size(); ++j) {
    h.add(space.planned_joints[j]);
    h.add(space.lower[j]);
    h.add(space.upper[j]);
    h.add(static_cast<bool>(space.continuous[j]));
  }
  for (const double v : space.fixed_positions) h.add(v);
  // The settings a roadmap's milestones and edges depend on, each under its name (the
  // hash of files written before the settings were typed).
  const PlannerSettings& s = scene.planner;
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"distance_weights.position", s.distance_weights.position},
        {"distance_weights.rotation", s.distance_weights.rotation},
        {"distance_weights.joint", s.distance_weights.joint},
        {"delta_fraction", s.delta_fraction},
        {"edge_resolution", s.edge_resolution},
        {"max_displacement", s.max_displacement}}) {
    h.add(std::string(name));
    h.add(value);
  }
  return h.value();
}

void save_roadmap(const Roadmap& roadmap, const Scene& scene, const std::string& path) {
  std::ostringstream image;
  image.write(kMagic, sizeof(kMagic) - 1);
  put(image, scene_fingerprint(scene));
  put(image, static_cast<std::int32_t>(roadmap.width()));
  put(image, static_cast<std::uint64_t>(roadmap.vertex_count()));
  put(image, static_cast<std::uint64_t>(roadmap.edge_count()));
  image.write(reinterpret_cast<const char*>(roadmap.vertices().data()),
              roadmap.vertices().size() * sizeof(float));
  for (const RoadmapEdge& e : roadmap.edges()) {
    put(image, e.a);
    put(image, e.b);
    put(image, e.length);
    put(image, static_cast<std::uint8_t>(e.state));
  }
  const std::string data = image.str();
  Hash checksum;
  checksum.bytes(data.data(), data.size());
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(data.data(), data.size());
    put(out, checksum.value());
  });
}

namespace {

// Why row q (shape: [space.width()]) is no configuration of the scene, or "": as
// ConfigurationSpace::out_of_bounds, but a base position within the slack of float
// rounding past a bound (a milestone on the bound) is within.
std::string row_problem(const Scene& scene, const float* q) {
  const ConfigurationSpace& space = scene.space;
  std::vector<float> rest(q, q + space.width());
  for (int k = 0; k < space.position_width(); ++k) {
    const double slack = 1e-6 * std::max(1.0, space.base_max[k] - space.base_min[k]);
    if (!(q[k] >= space.base_min[k] - slack && q[k] <= space.base_max[k] + slack)) {
      return space.out_of_bounds(scene.robot, q);
    }
    rest[k] = static_cast<float>((space.base_min[k] + space.base_max[k]) / 2);  // judged
  }
  return space.out_of_bounds(scene.robot, rest.data());
}

}  // namespace

Roadmap load_roadmap(const Scene& scene, const std::string& path) {
  const SourceLocation file{path, 0, ""};
  const std::uintmax_t size = check_input_file(path, kRoadmapFile, file);
  auto damaged = [&](const std::string& key, const std::string& why) {
    return InputError({path, 0, key}, "roadmap file is damaged (" + why + "); build it again");
  };
  // The header first: its counts must give the file's size before the file is read.
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "roadmap file cannot be opened; check its permissions");
  std::string data(std::min<std::uintmax_t>(size, kHeaderBytes), '\0');
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  if (data.size() < kMagicBytes || data.compare(0, kMagicBytes, kMagic) != 0) {
    throw InputError(file, "not a gplanner roadmap file; give a file written by --save-roadmap");
  }
  if (size < kHeaderBytes + kChecksumBytes) throw InputError(file, kTruncated);
  std::int32_t width = 0;
  std::uint64_t vertices = 0, edges = 0;
  std::memcpy(&width, data.data() + kMagicBytes + 8, sizeof(width));
  std::memcpy(&vertices, data.data() + kMagicBytes + 12, sizeof(vertices));
  std::memcpy(&edges, data.data() + kMagicBytes + 20, sizeof(edges));
  // Before the sizes: another scene may have another width. A file is another scene's
  // only where it is whole by its own header and checksum; otherwise it is damaged.
  const std::uintmax_t body = size - kHeaderBytes - kChecksumBytes;
  std::uint64_t fingerprint = 0;
  std::memcpy(&fingerprint, data.data() + kMagicBytes, sizeof(fingerprint));
  if (fingerprint != scene_fingerprint(scene)) {
    const bool sized = width > 0 && vertices <= body / (sizeof(float) * width) &&
                       edges <= body / kEdgeBytes &&
                       vertices * width * sizeof(float) + edges * kEdgeBytes == body;
    if (!sized) throw damaged("", "its header's width and counts do not give its size");
    std::string whole(static_cast<std::size_t>(size), '\0');
    std::ifstream again(path, std::ios::binary);
    again.read(whole.data(), static_cast<std::streamsize>(size));
    Hash checksum;
    checksum.bytes(whole.data(), whole.size() - kChecksumBytes);
    std::uint64_t stored = 0;
    std::memcpy(&stored, whole.data() + whole.size() - kChecksumBytes, sizeof(stored));
    if (static_cast<std::uintmax_t>(again.gcount()) != size || stored != checksum.value())
      throw damaged("", "checksum mismatch");
    throw InputError(file, "roadmap belongs to another scene, or to other settings of '" +
                               scene.file +
                               "' (robot, obstacles, bounds, weights, tolerance or resolution "
                               "differ); build it again for this scene");
  }
  if (width != scene.space.width() || vertices > body / (sizeof(float) * std::max(width, 1)) ||
      edges > body / kEdgeBytes || vertices * width * sizeof(float) + edges * kEdgeBytes != body) {
    throw damaged("", "its header's width and counts do not give its size");
  }
  if (vertices > std::numeric_limits<std::uint32_t>::max()) {
    throw damaged("", "more milestones than edges can name");
  }
  data.resize(static_cast<std::size_t>(size));
  in.read(data.data() + kHeaderBytes, static_cast<std::streamsize>(size - kHeaderBytes));
  if (static_cast<std::uintmax_t>(in.gcount()) != size - kHeaderBytes) {
    throw InputError(file, kTruncated);
  }
  const std::size_t checked = data.size() - kChecksumBytes;
  Hash checksum;
  checksum.bytes(data.data(), checked);
  std::uint64_t stored = 0;
  std::memcpy(&stored, data.data() + checked, sizeof(stored));
  if (stored != checksum.value()) throw damaged("", "checksum mismatch");
  Reader reader(data, path);
  char skip[kHeaderBytes];
  reader.take(skip, kHeaderBytes);
  Roadmap roadmap(width);
  std::vector<float> q(width);
  for (std::uint64_t v = 0; v < vertices; ++v) {
    reader.take(q.data(), sizeof(float) * width);
    const std::string problem = row_problem(scene, q.data());
    if (!problem.empty()) throw damaged("milestone " + std::to_string(v), problem);
    roadmap.add_vertex(q.data());
  }
  for (std::uint64_t e = 0; e < edges; ++e) {
    const auto a = reader.get<std::uint32_t>();
    const auto b = reader.get<std::uint32_t>();
    const auto length = reader.get<float>();
    const auto state = reader.get<std::uint8_t>();
    const std::string key = "edge " + std::to_string(e);
    if (a >= vertices || b >= vertices || a >= b) {
      throw damaged(key, "it joins milestones " + std::to_string(a) + " and " + std::to_string(b));
    }
    if (!std::isfinite(length) || length < 0) {
      std::ostringstream problem;
      problem << "its length is " << length << ", not a finite distance of 0 or more";
      throw damaged(key, problem.str());
    }
    if (state > 2) throw damaged(key, "its state " + std::to_string(state) + " is unknown");
    if (roadmap.find_edge(a, b) >= 0) throw damaged(key, "it joins two milestones twice");
    roadmap.add_edge(a, b, length, static_cast<EdgeState>(state));
  }
  return roadmap;
}

}  // namespace gplanner

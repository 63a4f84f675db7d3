#include "apps/hostile/case_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "apps/hostile/catalogue_case.h"
#include "apps/hostile/roadmap_edits.h"
#include "test_support.h"

namespace gplanner::hostile {
namespace {

namespace fs = std::filesystem;

const char* const kSceneYaml = R"(name: tiny
narrowest_passage: the gaps beside the wall, 0.4 m wide for a 0.2 m cube
robot:
  mesh: cube.obj
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
  seed: 1
  roadmap: {milestones: 200}
)";

const char* const kArmUrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry></collision>
  </link>
  <link name="lower">
    <collision><origin xyz="0 0 0.15"/><geometry><mesh filename="cube.obj"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <origin xyz="0 0 0.05"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/>
    <child link="lower"/>
    <origin xyz="0 0 0.3"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="1" velocity="1"/>
  </joint>
</robot>
)";

const char* const kArmSrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <disable_collisions link1="base" link2="lower" reason="Never"/>
</robot>
)";

const char* const kArmYaml = R"(name: arm
narrowest_passage: none; the arm swings over a box
robot:
  urdf: arm.urdf
  srdf: arm.srdf
  planned_joints: [shoulder, elbow]
obstacles:
  - box: [0.2, 0.2, 0.2]
    pose: {xyz: [0, 0, 0.9]}
start:
  joints: {shoulder: -1.0, elbow: 0.5}
goal:
  joints: {shoulder: 1.0, elbow: -0.5}
planner:
  roadmap: {milestones: 100}
)";

std::string fixture_text(const std::string& name) {
  if (name == "cube.obj") return testing::kCubeObj;
  if (name == "scene.yaml") return kSceneYaml;
  if (name == "arm.urdf") return kArmUrdf;
  if (name == "arm.srdf") return kArmSrdf;
  if (name == "arm.yaml") return kArmYaml;
  throw std::runtime_error("no fixture named '" + name + "'");
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string hex_bytes(const std::string& hex) {
  std::string bytes;
  std::string digits;
  for (const char c : hex) {
    if (std::isxdigit(static_cast<unsigned char>(c))) digits += c;
    if (digits.size() == 2) {
      bytes += static_cast<char>(std::stoi(digits, nullptr, 16));
      digits.clear();
    }
  }
  return bytes;
}

// A fixture with each [from, to] replaced (every occurrence; the text must hold it),
// then prepend and append.
std::string edited_fixture(const YAML::Node& spec, const std::string& folder) {
  std::string text = fixture_text(spec["from"].as<std::string>());
  for (const YAML::Node& pair : spec["replace"]) {
    const std::string from = pair[0].as<std::string>();
    const std::string to = build_text(pair[1], folder);
    std::size_t at = text.find(from);
    if (at == std::string::npos)
      throw std::runtime_error("'" + from + "' is not in " + spec["from"].as<std::string>());
    for (; at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  }
  if (spec["prepend"]) text = build_text(spec["prepend"], folder) + text;
  if (spec["append"]) text += build_text(spec["append"], folder);
  return text;
}

// A URDF chain of `links` small boxes joined by revolute joints j1, j2, ...
std::string urdf_chain(int links) {
  std::string text = "<?xml version=\"1.0\"?>\n<robot name=\"chain\">\n";
  for (int i = 0; i < links; ++i) {
    text +=
        "  <link name=\"l" + std::to_string(i) +
        "\"><collision><geometry><box size=\"0.01 0.01 0.01\"/></geometry></collision></link>\n";
  }
  for (int i = 1; i < links; ++i) {
    text += "  <joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"l" +
            std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
            "\"/><origin xyz=\"0 0 0.02\"/><axis xyz=\"0 1 0\"/>"
            "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  return text + "</robot>\n";
}

std::uint64_t content_hash(const fs::path& path, std::uintmax_t size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  constexpr std::uintmax_t kWhole = 16u << 20, kPart = 1u << 20;
  std::string bytes;
  if (size <= kWhole) {
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } else {
    bytes.resize(2 * kPart);
    in.read(&bytes[0], kPart);
    in.seekg(static_cast<std::streamoff>(size - kPart));
    in.read(&bytes[kPart], kPart);
  }
  return std::hash<std::string_view>()(bytes);
}

}  // namespace

void write_fixtures(const std::string& folder) {
  for (const char* name : {"cube.obj", "scene.yaml", "arm.urdf", "arm.srdf", "arm.yaml"})
    write_bytes(fs::path(folder) / name, fixture_text(name));
}

void create_file(const std::string& folder, const std::string& name, const YAML::Node& spec) {
  const fs::path path = fs::path(folder) / name;
  fs::create_directories(path.parent_path());
  std::error_code ignored;
  if (fs::is_symlink(path) || fs::exists(path)) fs::remove(path, ignored);
  if (spec.IsScalar()) {
    write_bytes(path, build_text(spec, folder));
  } else if (spec["from"]) {
    write_bytes(path, edited_fixture(spec, folder));
  } else if (spec["hex"]) {
    write_bytes(path, hex_bytes(spec["hex"].as<std::string>()));
  } else if (spec["sparse"]) {
    write_bytes(path, spec["text"] ? build_text(spec["text"], folder) : "");
    fs::resize_file(path, spec["sparse"].as<std::uintmax_t>());
  } else if (spec["fifo"]) {
    if (mkfifo(path.c_str(), 0644) != 0) throw std::runtime_error("mkfifo " + path.string());
  } else if (spec["symlink"]) {
    fs::create_symlink(build_text(spec["symlink"], folder), path);
  } else if (spec["hardlink"]) {
    fs::create_hard_link(fs::path(folder) / spec["hardlink"].as<std::string>(), path);
  } else if (spec["urdf_chain"]) {
    write_bytes(path, urdf_chain(spec["urdf_chain"].as<int>()));
  } else if (spec["folder"]) {
    fs::create_directories(path);
  } else if (spec["device"]) {
    // A character device made here (root), never the system's own /dev nodes: a run
    // that replaced it would break the machine.
    const unsigned major_number = spec["device"][0].as<unsigned>();
    const unsigned minor_number = spec["device"][1].as<unsigned>();
    if (mknod(path.c_str(), S_IFCHR | 0666, makedev(major_number, minor_number)) != 0) {
      // Not root: a symlink to the same kind of node (written through, it is still
      // refused; replacing it harms nothing).
      fs::create_symlink(major_number == 1 && minor_number == 5 ? "/dev/zero" : "/dev/null", path);
    }
  } else if (spec["roadmap"]) {
    write_bytes(path, roadmap_file(folder, spec["roadmap"]));
  } else if (spec["text"] || spec["parts"]) {
    write_bytes(path, build_text(spec, folder));
  } else {
    throw std::runtime_error("no way to create " + name + " given");
  }
  if (spec.IsMap() && spec["mode"]) {
    fs::permissions(path,
                    static_cast<fs::perms>(std::stoul(spec["mode"].as<std::string>(), nullptr, 8)));
  }
}

EntryState entry_state(const std::string& path) {
  EntryState state;
  struct stat info;
  if (lstat(path.c_str(), &info) != 0) {
    state.type = '-';
    return state;
  }
  state.mode = info.st_mode & 07777;
  state.mtime_ns =
      static_cast<std::int64_t>(info.st_mtim.tv_sec) * 1000000000 + info.st_mtim.tv_nsec;
  if (S_ISREG(info.st_mode)) {
    state.type = 'f';
    state.size = static_cast<std::uintmax_t>(info.st_size);
    state.content = content_hash(path, state.size);
  } else if (S_ISDIR(info.st_mode)) {
    state.type = 'd';
    state.mtime_ns = 0;  // a folder's time changes with any file made and removed in it
  } else if (S_ISLNK(info.st_mode)) {
    state.type = 'l';
    std::error_code error;
    state.link_target = fs::read_symlink(path, error).string();
  } else if (S_ISFIFO(info.st_mode)) {
    state.type = 'p';
  } else if (S_ISCHR(info.st_mode)) {
    state.type = 'c';
    state.size = info.st_rdev;
  } else if (S_ISBLK(info.st_mode)) {
    state.type = 'b';
    state.size = info.st_rdev;
  } else {
    state.type = 's';
  }
  return state;
}

std::map<std::string, EntryState> snapshot(const std::string& folder) {
  std::map<std::string, EntryState> entries;
  std::error_code error;
  for (fs::recursive_directory_iterator
           it(folder, fs::directory_options::skip_permission_denied, error),
       end;
       it != end; it.increment(error)) {
    if (error) break;
    entries[it->path().lexically_relative(folder).string()] = entry_state(it->path().string());
  }
  return entries;
}

void give_to(const std::string& folder, int user) {
  if (lchown(folder.c_str(), user, user) != 0) throw std::runtime_error("cannot chown " + folder);
  std::error_code error;
  for (fs::recursive_directory_iterator it(folder, error), end; it != end; it.increment(error)) {
    if (error) break;
    if (lchown(it->path().c_str(), user, user) != 0)
      throw std::runtime_error("cannot chown " + it->path().string());
  }
}

void make_removable(const std::string& folder) {
  std::error_code error;
  for (fs::recursive_directory_iterator it(folder, error), end; it != end; it.increment(error)) {
    if (error) break;
    if (!it->is_symlink() && it->is_directory())
      fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, error);
  }
  fs::permissions(folder, fs::perms::owner_all, fs::perm_options::add, error);
}

}  // namespace gplanner::hostile

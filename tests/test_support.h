#pragma once
// Shared by the tests: where the project and the real robot data are, scratch folders,
// and running the gplan program.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace gplanner::testing {

// The project root: $GPLANNER_ROOT, else the source folder this binary was built from,
// else (when that folder is gone) the working folder if it holds scenes/.
std::string project_root();

// The real robot data: $GPLANNER_SHARED_DATA, else ../shared/data beside the project.
// Empty when the folder does not exist (tests needing it skip).
std::string shared_data();

// A fresh, empty folder for one test, removed when the object dies.
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  const std::string& path() const { return path_; }
  // Writes `text` to path()/name and returns the full path.
  std::string write(const std::string& name, const std::string& text) const;

 private:
  std::string path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// The whole content of the file at `path` (empty when it cannot be read).
std::string read_file(const std::string& path);

// The fields of one line of text split at `separator` (no quoting; a line that ends in
// the separator ends with an empty field).
std::vector<std::string> split_fields(const std::string& line, char separator = ',');

// `text` in single quotes, for run_gplan's shell syntax (text without quotes of its own).
inline std::string shell_quoted(const std::string& text) { return "'" + text + "'"; }

// Runs the gplan program built beside the tests with `arguments` (shell syntax); where
// $GPLANNER_GPLAN is set, that command line instead (e.g. ".gpu/run .gpu/bin/gplan").
CommandResult run_gplan(const std::string& arguments);

// Runs `executable` with `arguments` (shell syntax), standard output and error together;
// where the environment variable `variable` (if not null) is set, that command line
// instead.
CommandResult run_program(const char* variable, const std::string& executable,
                          const std::string& arguments);

// Runs `body` in a child process whose address space is held to what it maps now plus
// `spare` bytes, so that threads fail to start there (each needs a stack of megabytes):
// returns 0 when body returned true, 1 when false, 2 when it threw, and 128 + the signal
// when the child died (std::terminate's abort: 134).
int run_with_address_space_to_spare(std::size_t spare, const std::function<bool()>& body);

// A closed cube of side 0.2 centred at the origin, faces counter-clockwise seen from
// outside, as an OBJ file's text.
inline constexpr const char* kCubeObj =
    "v -0.1 -0.1 -0.1\nv 0.1 -0.1 -0.1\nv 0.1 0.1 -0.1\nv -0.1 0.1 -0.1\n"
    "v -0.1 -0.1 0.1\nv 0.1 -0.1 0.1\nv 0.1 0.1 0.1\nv -0.1 0.1 0.1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// A scene named `name` of the cube above (cube.obj, beside the scene) as a rigid robot
// among `obstacles` (YAML list entries, a line "  - ..." each), from start x = -1 to goal
// x = 1 within x -2 to 2, y -1.5 to 1.5, z -1 to 1.
inline std::string cube_scene(const std::string& name, const std::string& obstacles) {
  return "name: " + name + "\nrobot:\n  mesh: cube.obj\nobstacles:\n" + obstacles +
         R"(bounds:
  min: [-2, -1.5, -1]
  max: [2, 1.5, 1]
start:
  base: {xyz: [-1, 0, 0], quat_wxyz: [1, 0, 0, 0]}
goal:
  base: {xyz: [1, 0, 0], quat_wxyz: [1, 0, 0, 0]}
)";
}

// A scene of the cube above (cube.obj, beside the scene) as a rigid robot, and a wall 2 cm
// thick across x = 0, from start x = -1 to goal x = 1.
inline const std::string kCubeAndThinWallScene =
    cube_scene("thin_wall", "  - box: [0.02, 10, 10]\n");

}  // namespace gplanner::testing

#pragma once
// Output paths checked before any work: every file a run writes is a regular file, or
// a new one, in a folder we may write and create files in; never a folder, device,
// FIFO or socket; never the same file as one the run reads or another it writes.
// Symbolic links are followed: writing a link writes its target, the link stays.

#include <sys/types.h>

#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"

namespace gplanner {

// An output that must not be written. Message: "OPTION PATH: PROBLEM; WHAT TO CHANGE"
// (just "PATH: ..." where no option named it).
class OutputPathError : public InputError {
 public:
  OutputPathError(const std::string& option, const std::string& path, const std::string& problem);
};

// A file a run reads or writes, and what names it in messages ("--out", "the scene
// file", "a file the scene loads").
struct NamedFile {
  std::string name;
  std::string path;
};

// Where writing a path lands, links resolved, and what is there now.
struct OutputTarget {
  std::string path;  // the file to create or replace: links followed, its folder canonical
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  mode_t mode = 0;  // permission bits of the file there now (exists)
  uid_t owner = 0;
  gid_t group = 0;
};

// Resolves `path` (named by `option`, which may be empty) and checks that it can be
// written: a non-empty name of a file, not a folder, device, FIFO or socket, in an
// existing folder we may write and create files in, writable itself where it exists.
// Filesystem failures (a link loop, a name too long, permission denied) become
// OutputPathError naming the option and the path.
OutputTarget writable_output_target(const std::string& option, const std::string& path);

// Checks every output with writable_output_target, then that no output is the same
// file (device and inode where it exists, the resolved path where it is new) as an
// input or as another output. Inputs that do not exist are skipped (reading them fails
// on its own). Throws OutputPathError naming the output, and the input or other output
// it collides with. Run once before reading anything and again once the inputs are
// known (a scene's meshes, URDF and SRDF: Scene::input_files).
void check_output_paths(const std::vector<NamedFile>& outputs,
                        const std::vector<NamedFile>& inputs);

}  // namespace gplanner

#pragma once
// The one way every loader opens an input file (scene, mesh and what a mesh names,
// URDF, SRDF, roadmap): it must be a regular file no larger than the limit for its kind,
// checked before anything reads it. Anything else is an InputError that says what the
// path is instead (a folder, a device, a FIFO, a socket, a broken symbolic link, a link
// loop, a name too long, no permission) and what to change.

#include <cstdint>
#include <string>

#include "gplanner/planner/scene/input_error.h"

namespace gplanner {

// A kind of input file: what it is called in messages and how large it may be.
struct InputFileKind {
  const char* what;        // "scene file", "mesh", ...
  std::uintmax_t max_bytes;
};

inline constexpr std::uintmax_t kMiB = std::uintmax_t(1) << 20;
inline constexpr InputFileKind kSceneFile{"scene file", 16 * kMiB};
inline constexpr InputFileKind kUrdfFile{"URDF", 64 * kMiB};
inline constexpr InputFileKind kSrdfFile{"SRDF", 16 * kMiB};
inline constexpr InputFileKind kMeshFile{"mesh", 1024 * kMiB};
inline constexpr InputFileKind kRoadmapFile{"roadmap file", 16384 * kMiB};
inline constexpr InputFileKind kMoveItSceneFile{"MoveIt planning scene", 64 * kMiB};
inline constexpr InputFileKind kMoveItRequestFile{"MoveIt motion plan request", 16 * kMiB};

// Why `path` cannot be read as a `kind` file ("is a folder, not a file; name a mesh
// file"), or "" when it is a readable regular file within the kind's size limit.
// `size` (when given) receives the file's size.
std::string input_file_problem(const std::string& path, const InputFileKind& kind,
                               std::uintmax_t* size = nullptr);

// Throws InputError at `where` ("KIND 'PATH' PROBLEM") unless `path` is a readable
// regular file within the kind's limit; returns its size.
std::uintmax_t check_input_file(const std::string& path, const InputFileKind& kind,
                                const SourceLocation& where);

// check_input_file, then the whole file. The file is opened without blocking and checked
// again once open, so that a FIFO or device put in its place meanwhile is refused too.
std::string read_input_file(const std::string& path, const InputFileKind& kind,
                            const SourceLocation& where);

}  // namespace gplanner

#include "guarded_io_system.h"

#include <sys/stat.h>

#include <algorithm>
#include <string>

#include "gplanner/planner/scene/input_file.h"

namespace gplanner {

bool GuardedIOSystem::Exists(const char* file) const {
  struct stat st {};
  return file != nullptr && stat(file, &st) == 0;
}

Assimp::IOStream* GuardedIOSystem::Open(const char* file, const char* mode) {
  const std::string path = file ? file : "";
  const std::string how = mode ? mode : "rb";
  std::string problem;
  if (how.find_first_of("wa+") != std::string::npos) {
    problem = "would be opened for writing by the mesh reader; gplanner never writes inputs";
  } else {
    problem = input_file_problem(path, kMeshFile);
    if (problem.rfind("does not exist", 0) == 0) return nullptr;  // assimp copes
  }
  if (!problem.empty()) {
    if (refusal_.empty()) refusal_ = "'" + path + "' " + problem;
    return nullptr;
  }
  if (std::find(files_read_.begin(), files_read_.end(), path) == files_read_.end()) {
    files_read_.push_back(path);
  }
  return Assimp::DefaultIOSystem::Open(file, mode);
}

}  // namespace gplanner

#include "gplanner/planner/output/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace gplanner {

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (fs::is_directory(target)) throw std::runtime_error(path + " is a folder, not a file");
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(folder)) {
    throw std::runtime_error("folder " + folder.string() + " does not exist");
  }
  const std::string temporary =
      (folder / ("." + target.filename().string() + ".tmp." + std::to_string(getpid()))).string();
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out)
        throw std::runtime_error("cannot create " + temporary + ": " + std::strerror(errno));
      write(out);
      out.flush();
      if (!out) throw std::runtime_error("writing " + temporary + " failed (disk full?)");
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
      throw std::runtime_error("cannot replace " + path + ": " + std::strerror(errno));
    }
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
}

}  // namespace gplanner

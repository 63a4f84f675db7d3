#include "gplanner/planner/output/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gplanner/planner/output/output_paths.h"

namespace gplanner {
namespace {

// Permission bits for a new file: what the umask leaves of rw-rw-rw-, as creating it
// directly would give. The umask is read from /proc (setting it to read it would race
// with other threads creating files); where /proc does not say, umask() it is.
mode_t new_file_mode() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Umask:", 0) == 0)
      return 0666 & ~static_cast<mode_t>(std::strtoul(line.c_str() + 6, nullptr, 8));
  }
  const mode_t mask = umask(0);
  umask(mask);
  return 0666 & ~mask;
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  // Refuses folders, devices, FIFOs and sockets, follows symbolic links to the file
  // they name, and checks that the folder takes new files.
  const OutputTarget target = writable_output_target("", path);
  const fs::path file(target.path);
  // A fresh temporary name, created exclusively (mkstemp), so that nothing planted
  // beside the target is followed; short enough for any file name.
  std::string pattern =
      (file.parent_path() / ("." + file.filename().string().substr(0, 200) + ".XXXXXX")).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int descriptor = mkstemp(name.data());
  if (descriptor < 0) {
    throw std::runtime_error("cannot write " + path + ": cannot create a file in " +
                             file.parent_path().string() + ": " + std::strerror(errno));
  }
  const std::string temporary(name.data());
  bool descriptor_open = true;
  try {
    // The content first (through the name, while the descriptor keeps the file ours),
    // then on disk, then the permission bits (a mode without write permission for us,
    // a replaced file's, must not stop the writing), then the rename.
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
      write(out);
      out.flush();
      if (!out) throw std::runtime_error("writing " + path + " failed (disk full?)");
    }
    if (fsync(descriptor) != 0) {
      throw std::runtime_error("writing " + path + " failed: " + std::strerror(errno));
    }
    const mode_t mode = target.exists ? target.mode : new_file_mode();
    const int chmod_error = fchmod(descriptor, mode) == 0 ? 0 : errno;
    // Replacing a file keeps its owner where we may (root replacing a user's file); an
    // ordinary user cannot give a file away, and the file becomes theirs.
    if (target.exists && fchown(descriptor, target.owner, target.group) != 0) errno = 0;
    close(descriptor);
    descriptor_open = false;
    if (chmod_error != 0) {
      throw std::runtime_error("cannot write " + path + ": " + std::strerror(chmod_error));
    }
    if (std::rename(temporary.c_str(), target.path.c_str()) != 0) {
      throw std::runtime_error("cannot replace " + path + ": " + std::strerror(errno));
    }
    // The rename itself on disk: the folder synced (where it can be opened).
    const int folder = open(file.parent_path().c_str(), O_RDONLY | O_DIRECTORY);
    if (folder >= 0) {
      fsync(folder);
      close(folder);
    }
  } catch (...) {
    if (descriptor_open) close(descriptor);
    std::remove(temporary.c_str());
    throw;
  }
}

}  // namespace gplanner

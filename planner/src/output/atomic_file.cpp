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

// An anonymous file in `folder` (O_TMPFILE): nothing of it is visible until it is linked,
// so a process killed while writing leaves nothing behind. -1 where the file system
// cannot make one (then a named temporary is used).
int anonymous_file(const std::string& folder) {
#ifdef O_TMPFILE
  return open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
#else
  (void)folder;
  return -1;
#endif
}

// Links the anonymous file `descriptor` into `folder` under a fresh hidden name beside
// `base` and returns that name.
std::string link_anonymous_file(int descriptor, const std::filesystem::path& folder,
                                const std::string& base, const std::string& path) {
  const std::string proc = "/proc/self/fd/" + std::to_string(descriptor);
  for (int attempt = 0; attempt < 100; ++attempt) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, ".%06x", static_cast<unsigned>(std::rand()) & 0xffffff);
    const std::string name = (folder / ("." + base + suffix)).string();
    if (linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return name;
    if (errno != EEXIST) break;
  }
  throw std::runtime_error("cannot write " + path + ": cannot name the written file in " +
                           folder.string() + ": " + std::strerror(errno));
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  // Refuses folders, devices, FIFOs and sockets, follows symbolic links to the file
  // they name, and checks that the folder takes new files.
  const OutputTarget target = writable_output_target("", path);
  const fs::path file(target.path);
  const std::string base = file.filename().string().substr(0, 200);
  // Written into an anonymous file where the file system makes one, so that a kill
  // (SIGKILL, a crash) while writing leaves nothing; it gets a hidden name only once
  // written, just before the rename. Elsewhere a fresh temporary name, created
  // exclusively (mkstemp), so that nothing planted beside the target is followed.
  int descriptor = anonymous_file(file.parent_path().string());
  const bool anonymous = descriptor >= 0;
  std::string temporary;
  if (!anonymous) {
    std::string pattern = (file.parent_path() / ("." + base + ".XXXXXX")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    descriptor = mkstemp(name.data());
    if (descriptor < 0) {
      throw std::runtime_error("cannot write " + path + ": cannot create a file in " +
                               file.parent_path().string() + ": " + std::strerror(errno));
    }
    temporary = name.data();
  }
  bool descriptor_open = true;
  try {
    // The content first (through a name of the file, while the descriptor keeps it
    // ours), then on disk, then the permission bits (a mode without write permission for
    // us, a replaced file's, must not stop the writing), then the rename.
    {
      const std::string through =
          anonymous ? "/proc/self/fd/" + std::to_string(descriptor) : temporary;
      std::ofstream out(through, std::ios::binary | std::ios::trunc);
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
    if (chmod_error != 0) {
      throw std::runtime_error("cannot write " + path + ": " + std::strerror(chmod_error));
    }
    if (anonymous) temporary = link_anonymous_file(descriptor, file.parent_path(), base, path);
    close(descriptor);
    descriptor_open = false;
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
    if (!temporary.empty()) std::remove(temporary.c_str());
    throw;
  }
}

}  // namespace gplanner

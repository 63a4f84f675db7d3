#include "gplanner/planner/output/output_paths.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace gplanner {
namespace {

namespace fs = std::filesystem;

// Symbolic links followed one after another before giving up (Linux's own limit).
constexpr int kMaxLinks = 40;

// A path as messages show it: whole up to 200 characters, longer ones cut in the middle.
std::string shown(const std::string& path) {
  return path.size() <= 200 ? path : path.substr(0, 120) + "..." + path.substr(path.size() - 60);
}

std::string option_and_path(const std::string& option, const std::string& path) {
  return option.empty() ? shown(path) : option + " " + shown(path);
}

// What a failed system call on a path means, and what to do about it.
std::string explain(int error) {
  switch (error) {
    case ELOOP:
      return "too many symbolic links (a loop?); point the links at a file";
    case ENAMETOOLONG:
      return "the name is too long for the file system; choose a shorter one";
    case EACCES:
    case EPERM:
      return "permission denied; choose a folder you may write";
    case ENOTDIR:
      return "a part of the path is not a folder; fix the path";
    case ENOENT:
      return "the folder does not exist; create it or write elsewhere";
    case EROFS:
      return "the file system is read-only; write elsewhere";
    default:
      return std::string(std::strerror(error)) + "; choose another path";
  }
}

const char* kind_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

bool same_file(const struct stat& a, const OutputTarget& b) {
  return b.exists && a.st_dev == b.device && a.st_ino == b.inode;
}

bool same_file(const OutputTarget& a, const OutputTarget& b) {
  if (a.exists != b.exists) return false;
  return a.exists ? a.device == b.device && a.inode == b.inode : a.path == b.path;
}

}  // namespace

OutputPathError::OutputPathError(const std::string& option, const std::string& path,
                                 const std::string& problem)
    : InputError({option_and_path(option, path), 0, ""}, problem) {}

OutputTarget writable_output_target(const std::string& option, const std::string& path) {
  if (path.empty()) {
    throw OutputPathError(option, "''", "an empty file name; name the file to write");
  }
  // The last component, link after link, even where the last target does not exist
  // yet (a dangling link creates its target, as writing through it would).
  fs::path current(path);
  struct stat status {};
  bool exists = false;
  int links = 0;
  for (;; ++links) {
    if (lstat(current.c_str(), &status) != 0) {
      if (errno != ENOENT) throw OutputPathError(option, path, explain(errno));
      exists = false;
      break;
    }
    exists = true;
    if (!S_ISLNK(status.st_mode)) break;
    if (links == kMaxLinks) throw OutputPathError(option, path, explain(ELOOP));
    std::error_code error;
    const fs::path target = fs::read_symlink(current, error);
    if (error) throw OutputPathError(option, path, explain(error.value()));
    current = target.is_absolute() ? target : current.parent_path() / target;
  }
  const fs::path name = current.filename();
  if (name.empty() || name == "." || name == "..") {
    throw OutputPathError(option, path, "names a folder, not a file; add a file name");
  }
  const fs::path given_folder = current.has_parent_path() ? current.parent_path() : fs::path(".");
  std::error_code error;
  const fs::path folder = fs::canonical(given_folder, error);
  if (error) {
    const int code = error.value();
    // Through a link, say where it leads: the folder named is not in the path given.
    const std::string through =
        links > 0 ? " (the symbolic link leads to " + shown(current.string()) + ")" : "";
    const std::string problem = code == ENOENT
                                    ? "folder " + shown(given_folder.string()) + " does not exist" +
                                          through + "; create it or write elsewhere"
                                    : explain(code);
    throw OutputPathError(option, path, problem);
  }
  if (!fs::is_directory(folder, error)) {
    throw OutputPathError(option, path, given_folder.string() + " is not a folder; fix the path");
  }
  OutputTarget target;
  target.path = (folder / name).string();
  target.exists = exists;
  if (exists) {
    if (S_ISDIR(status.st_mode)) {
      throw OutputPathError(option, path, "is a folder, not a file; add a file name");
    }
    if (!S_ISREG(status.st_mode)) {
      throw OutputPathError(option, path,
                            std::string("is ") + kind_name(status.st_mode) +
                                ", not a regular file, and would be replaced by one; name a "
                                "regular file or a new one");
    }
    // Permission bits do not stop root; access() still sees a read-only file system.
    if (faccessat(AT_FDCWD, target.path.c_str(), W_OK, AT_EACCESS) != 0) {
      throw OutputPathError(option, path,
                            errno == EACCES ? "the file is not writable; change its "
                                              "permissions or write elsewhere"
                                            : explain(errno));
    }
    target.device = status.st_dev;
    target.inode = status.st_ino;
    target.mode = status.st_mode & 07777;
    target.owner = status.st_uid;
    target.group = status.st_gid;
  }
  // The file is written beside itself and renamed into place: the folder must take
  // new files, whether or not the file exists.
  if (faccessat(AT_FDCWD, folder.c_str(), W_OK | X_OK, AT_EACCESS) != 0) {
    throw OutputPathError(option, path,
                          errno == EACCES ? "cannot create files in folder " + folder.string() +
                                                "; change its permissions or write elsewhere"
                                          : explain(errno));
  }
  // Permission bits say too little (root passes them; /proc, /sys and full or
  // read-only file systems refuse anyway): a file is made there and removed at once.
  std::string probe = (folder / ".gplan-probe.XXXXXX").string();
  const int probe_fd = mkstemp(probe.data());
  if (probe_fd < 0) {
    const int code = errno;
    throw OutputPathError(option, path,
                          "cannot create files in folder " + shown(folder.string()) + " (" +
                              std::strerror(code) + "); write elsewhere");
  }
  close(probe_fd);
  unlink(probe.c_str());
  return target;
}

void check_output_paths(const std::vector<NamedFile>& outputs,
                        const std::vector<NamedFile>& inputs) {
  std::vector<OutputTarget> targets;
  for (const NamedFile& output : outputs) {
    const OutputTarget target = writable_output_target(output.name, output.path);
    for (const NamedFile& input : inputs) {
      struct stat status {};
      if (stat(input.path.c_str(), &status) != 0 || !same_file(status, target)) continue;
      throw OutputPathError(output.name, output.path,
                            "would overwrite " + input.name + " (" + shown(input.path) +
                                "), an input of this run; name another file");
    }
    for (std::size_t i = 0; i < targets.size(); ++i) {
      if (!same_file(targets[i], target)) continue;
      throw OutputPathError(output.name, output.path,
                            "is also " + outputs[i].name + " " + shown(outputs[i].path) +
                                "; give each output its own file");
    }
    targets.push_back(target);
  }
}

}  // namespace gplanner

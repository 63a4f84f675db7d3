#include "gplanner/planner/scene/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace gplanner {
namespace {

std::string describe_size(std::uintmax_t bytes) {
  if (bytes >= kMiB) return std::to_string(bytes / kMiB) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// What a stat() that failed with `error` says about `path`.
std::string stat_problem(const std::string& path, int error, const InputFileKind& kind) {
  const std::string fix = std::string("; give the path of a ") + kind.what;
  switch (error) {
    case ENOENT: {
      struct stat link {};
      if (lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
        return "is a broken symbolic link (its target does not exist); fix the link or the path";
      }
      return "does not exist; fix the path";
    }
    case ELOOP:
      return "is a symbolic link loop (links that lead back to themselves); fix the links or "
             "name the file itself";
    case ENAMETOOLONG:
      return "has a name too long for the file system; shorten the path";
    case EACCES:
      return "cannot be reached: no permission to enter a folder on its path; check the "
             "folders' permissions";
    case ENOTDIR:
      return "does not exist: part of its path is a file, not a folder; fix the path";
    default:
      return std::string("cannot be examined (") + std::strerror(error) + ")" + fix;
  }
}

// What `st` (not a regular file) is.
std::string kind_problem(const struct stat& st, const InputFileKind& kind) {
  const std::string fix = std::string("; give the path of a ") + kind.what;
  if (S_ISDIR(st.st_mode)) return "is a folder, not a file" + fix;
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device, not a file" + fix;
  if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe), not a file" + fix;
  if (S_ISSOCK(st.st_mode)) return "is a socket, not a file" + fix;
  return "is not a regular file" + fix;
}

std::string size_problem(std::uintmax_t size, const InputFileKind& kind) {
  return "is " + describe_size(size) + ", more than the " + describe_size(kind.max_bytes) +
         " a " + kind.what + " may have; give a smaller file";
}

[[noreturn]] void refuse(const std::string& path, const InputFileKind& kind,
                         const SourceLocation& where, const std::string& problem) {
  // The file itself at fault ("FILE: scene file does not exist") or one it names.
  const std::string named = where.file == path ? "" : " '" + path + "'";
  throw InputError(where, std::string(kind.what) + named + " " + problem);
}

// Closes a descriptor when it goes out of scope.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) close(fd);
  }
};

}  // namespace

std::string input_file_problem(const std::string& path, const InputFileKind& kind,
                               std::uintmax_t* size) {
  if (path.empty()) return std::string("is an empty name; give the path of a ") + kind.what;
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return stat_problem(path, errno, kind);
  if (!S_ISREG(st.st_mode)) return kind_problem(st, kind);
  if (access(path.c_str(), R_OK) != 0) return "cannot be read; check its permissions";
  const auto bytes = static_cast<std::uintmax_t>(st.st_size);
  if (size) *size = bytes;
  if (bytes > kind.max_bytes) return size_problem(bytes, kind);
  return "";
}

std::uintmax_t check_input_file(const std::string& path, const InputFileKind& kind,
                                const SourceLocation& where) {
  std::uintmax_t size = 0;
  const std::string problem = input_file_problem(path, kind, &size);
  if (!problem.empty()) refuse(path, kind, where, problem);
  return size;
}

std::string read_input_file(const std::string& path, const InputFileKind& kind,
                            const SourceLocation& where) {
  check_input_file(path, kind, where);
  // O_NONBLOCK: opening a FIFO swapped in since the check must not wait for a writer.
  const Descriptor file{open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
  if (file.fd < 0) refuse(path, kind, where, stat_problem(path, errno, kind));
  struct stat st {};
  if (fstat(file.fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    refuse(path, kind, where, kind_problem(st, kind));
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > kind.max_bytes) refuse(path, kind, where, size_problem(size, kind));
  std::string text(static_cast<std::size_t>(size), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = read(file.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse(path, kind, where, std::string("cannot be read (") + std::strerror(errno) + ")");
    if (n == 0) break;  // shrank meanwhile
    done += static_cast<std::size_t>(n);
  }
  text.resize(done);
  return text;
}

}  // namespace gplanner

#include "test_support.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <iterator>
#include <random>

namespace gplanner::testing {
namespace fs = std::filesystem;

std::string project_root() {
  const char* root = std::getenv("GPLANNER_ROOT");
  if (root && *root) return root;
  // Built here, run elsewhere (the GPU machine) from a copy of the project: the source
  // folder named at build time is not there, the working folder is.
  if (!fs::is_directory(fs::path(GPLANNER_SOURCE_DIR) / "scenes") && fs::is_directory("scenes")) {
    return fs::current_path().string();
  }
  return GPLANNER_SOURCE_DIR;
}

std::string shared_data() {
  const char* data = std::getenv("GPLANNER_SHARED_DATA");
  const fs::path folder =
      data && *data ? fs::path(data) : fs::path(project_root()) / ".." / "shared" / "data";
  return fs::is_directory(folder) ? fs::canonical(folder).string() : std::string();
}

ScratchFolder::ScratchFolder() {
  std::random_device entropy;
  path_ = (fs::temp_directory_path() /
           ("gplanner-test-" + std::to_string(getpid()) + "-" + std::to_string(entropy())))
              .string();
  fs::create_directories(path_);
}

ScratchFolder::~ScratchFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> split_fields(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::istringstream cells(line);
  for (std::string cell; std::getline(cells, cell, separator);) fields.push_back(cell);
  if (!line.empty() && line.back() == separator) fields.push_back("");
  return fields;
}

std::string ScratchFolder::write(const std::string& name, const std::string& text) const {
  const fs::path file = fs::path(path_) / name;
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
  return file.string();
}

CommandResult run_gplan(const std::string& arguments) {
  // $GPLANNER_GPLAN: how to start gplan where the build's path does not hold it (the
  // GPU machine: ".gpu/run .gpu/bin/gplan").
  return run_program("GPLANNER_GPLAN", GPLAN_EXECUTABLE, arguments);
}

CommandResult run_program(const char* variable, const std::string& executable,
                          const std::string& arguments) {
  const char* custom = variable ? std::getenv(variable) : nullptr;
  const std::string program = custom && *custom ? std::string(custom) : "'" + executable + "'";
  const std::string command = program + " " + arguments + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  std::size_t got = 0;
  while ((got = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), got);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

int run_with_address_space_to_spare(std::size_t spare, const std::function<bool()>& body) {
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    // The address space mapped now: /proc/self/statm's first field, in pages.
    std::size_t pages = 0;
    if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(statm, "%zu", &pages) != 1) pages = 0;
      std::fclose(statm);
    }
    const rlim_t limit = pages * sysconf(_SC_PAGE_SIZE) + spare;
    const rlimit address_space{limit, limit};
    if (pages == 0 || setrlimit(RLIMIT_AS, &address_space) != 0) _exit(3);
    int code = 2;
    try {
      code = body() ? 0 : 1;
    } catch (...) {
    }
    _exit(code);
  }
  int status = 0;
  if (waitpid(child, &status, 0) != child) return -1;
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace gplanner::testing

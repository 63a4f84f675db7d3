#include "program_main.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "command_line.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_error.h"

namespace gplan {
namespace {

// The exit code of one command (every error reported on stderr).
int run(const char* program, const char* usage, int argc, char** argv,
        int (*command)(int, char**)) {
  try {
    return command(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << program << ": " << gplanner::terminal_text(e.what()) << "\n" << usage;
    return 2;
  } catch (const gplanner::InputError& e) {
    std::cerr << program << ": " << gplanner::terminal_text(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << gplanner::terminal_text(e.what()) << "\n";
    return 1;
  }
}

// The process's open descriptors other than the NVIDIA driver's, and whether it holds
// any of the driver's (it made a CUDA context).
bool gpu_files(std::vector<int>* others) {
  bool gpu = false;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", error)) {
    const std::string target = std::filesystem::read_symlink(entry.path(), error).string();
    if (target.rfind("/dev/nvidia", 0) == 0) {
      gpu = true;
    } else {
      others->push_back(std::atoi(entry.path().filename().c_str()));
    }
  }
  return gpu;
}

// The NVIDIA driver tears a CUDA context down when the last of its files is closed:
// about 0.1 s on an H100, after the time limit, whoever waits for the program. So where
// it used the GPU a child keeps the driver's files (and nothing else: the caller's pipes
// and terminal are closed in it) until the program has ended, and the teardown is its.
void leave_gpu_teardown_to_a_child() {
  std::vector<int> others;
  if (!gpu_files(&others)) return;
  const pid_t parent = getpid();
  const pid_t child = fork();
  if (child != 0) return;  // the program itself, or no child: the teardown stays ours
  for (const int fd : others) close(fd);
  for (int i = 0; i < 5000 && getppid() == parent; ++i) usleep(1000);
  _exit(0);
}

}  // namespace

// Everything the command wrote is closed or flushed when it returns.
void program_main(const char* program, const char* usage, int argc, char** argv,
                  int (*command)(int, char**)) {
  const int code = run(program, usage, argc, argv, command);
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  leave_gpu_teardown_to_a_child();
  std::_Exit(code);
}

}  // namespace gplan

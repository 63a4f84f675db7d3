// gplan: the command line on YAML scene files (the commands: gplan_commands.h).

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "command_line.h"
#include "gplan_commands.h"
#include "gplanner/planner/output/text_escaping.h"
#include "gplanner/planner/scene/input_error.h"

namespace {

// The exit code of one command (every error reported on stderr).
int run(int argc, char** argv) {
  try {
    return gplan::run_command(argc, argv);
  } catch (const gplan::UsageError& e) {
    std::cerr << "gplan: " << gplanner::terminal_text(e.what()) << "\n" << gplan::kUsage;
    return 2;
  } catch (const gplanner::InputError& e) {
    std::cerr << "gplan: " << gplanner::terminal_text(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "gplan: error: " << gplanner::terminal_text(e.what()) << "\n";
    return 1;
  }
}

// Whether the process holds the NVIDIA driver's files open (it made a CUDA context).
bool holds_gpu() {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", error)) {
    const std::string target = std::filesystem::read_symlink(entry.path(), error).string();
    if (target.rfind("/dev/nvidia", 0) == 0) return true;
  }
  return false;
}

// The NVIDIA driver tears a CUDA context down when the last of its files is closed:
// about 0.1 s on an H100, after the time limit, whoever waits for gplan. So where gplan
// used the GPU a child keeps those files (with nothing else: no standard streams) until
// gplan has ended, and the teardown is its.
void leave_gpu_teardown_to_a_child() {
  const pid_t parent = getpid();
  const pid_t child = fork();
  if (child != 0) return;  // gplan itself, or no child: the teardown stays ours
  for (int fd = 0; fd <= 2; ++fd) close(fd);
  for (int i = 0; i < 5000 && getppid() == parent; ++i) usleep(1000);
  _exit(0);
}

}  // namespace

// Everything the command wrote is closed or flushed when it returns.
int main(int argc, char** argv) {
  const int code = run(argc, argv);
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  if (holds_gpu()) leave_gpu_teardown_to_a_child();
  std::_Exit(code);
}

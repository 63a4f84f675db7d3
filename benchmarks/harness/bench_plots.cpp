#include "bench_plots.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "harness/pipe_write.h"

extern char** environ;

namespace gplan {

// benchmarks/harness/plot_bench.py (with plot_common.py), generated into the build folder
// by benchmarks/CMakeLists.txt.
extern const unsigned char kPlotBenchScript[];
extern const std::size_t kPlotBenchScriptSize;
// benchmarks/harness/plot_error_time.py, the same way.
extern const unsigned char kPlotErrorTimeScript[];
extern const std::size_t kPlotErrorTimeScriptSize;
// benchmarks/harness/plot_broad_phase.py, the same way.
extern const unsigned char kPlotBroadPhaseScript[];
extern const std::size_t kPlotBroadPhaseScriptSize;

namespace {

constexpr const char* kInstall = "apt-get install python3-matplotlib";

// A pipe whose ends close on exec (the child gets its end through dup2).
struct Pipe {
  int read = -1;
  int write = -1;
  Pipe() {
    int ends[2];
    if (pipe2(ends, O_CLOEXEC) == 0) {
      read = ends[0];
      write = ends[1];
    }
  }
  ~Pipe() {
    close_read();
    close_write();
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  bool open() const { return read >= 0; }
  void close_read() {
    if (read >= 0) ::close(read);
    read = -1;
  }
  void close_write() {
    if (write >= 0) ::close(write);
    write = -1;
  }
};

// Starts `argv` (argv[0] looked up in PATH when it holds no '/') with standard input from
// `stdin_fd` and, where `stdout_fd` or `stderr_fd` is not -1, those outputs to it;
// returns the child's id, or -1 when it could not be started.
pid_t spawn(const std::vector<std::string>& argv, int stdin_fd, int stdout_fd, int stderr_fd) {
  std::vector<char*> args;
  for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  if (posix_spawn_file_actions_init(&actions) != 0) return -1;
  posix_spawn_file_actions_adddup2(&actions, stdin_fd, STDIN_FILENO);
  if (stdout_fd >= 0) posix_spawn_file_actions_adddup2(&actions, stdout_fd, STDOUT_FILENO);
  if (stderr_fd >= 0) posix_spawn_file_actions_adddup2(&actions, stderr_fd, STDERR_FILENO);
  pid_t pid = -1;
  const int error = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// The child's exit code, or minus the signal that ended it.
int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -SIGKILL;  // not ours to wait for: cannot happen
  }
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return WEXITSTATUS(status);
}

// Whether `python` runs and can import matplotlib: it must print matplotlib's version (a
// program that merely exits 0, /bin/true, is no python).
bool has_matplotlib(const std::string& python) {
  const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  Pipe output;
  if (null < 0 || !output.open()) {
    if (null >= 0) ::close(null);
    return false;
  }
  // Not from the working folder (first in sys.path with -c): a matplotlib/ of the user's.
  const char* const probe =
      "import sys\n"
      "if '' in sys.path: sys.path.remove('')\n"
      "import matplotlib\n"
      "print(matplotlib.__version__)\n";
  const pid_t pid = spawn({python, "-c", probe}, null, output.write, null);
  ::close(null);
  output.close_write();
  if (pid < 0) return false;
  std::string version;
  char buffer[256];
  for (;;) {
    const ssize_t n = ::read(output.read, buffer, sizeof buffer);
    if (n > 0) {
      if (version.size() < 4096) version.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  return wait_for(pid) == 0 && !version.empty() && version[0] >= '0' && version[0] <= '9';
}

// The python3 to run the script with, or empty (and `notice` set) when none can.
std::string find_python(std::string* notice) {
  const char* chosen = std::getenv("GPLANNER_PYTHON");
  if (chosen != nullptr && *chosen != '\0') {
    if (has_matplotlib(chosen)) return chosen;
    *notice = std::string("plots not drawn: GPLANNER_PYTHON=") + chosen +
              " is no python3 that can import matplotlib; set it to one that can, or unset "
              "it and install matplotlib (" +
              kInstall + ")";
    return "";
  }
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    if (has_matplotlib(python)) return python;
  }
  *notice = std::string(
                "plots not drawn: no python3 with matplotlib (tried python3 from "
                "PATH and /usr/bin/python3); install it: ") +
            kInstall;
  return "";
}

// Runs the embedded script `name` (its bytes `script_bytes`, `size` of them) on `csv` and
// `out_dir`, as draw_bench_plots says.
bool run_plot_script(const char* name, const unsigned char* script_bytes, std::size_t size,
                     const std::string& csv, const std::string& out_dir, std::string* notice) {
  notice->clear();
  const std::string python = find_python(notice);
  if (python.empty()) return false;

  Pipe script;
  if (!script.open()) {
    *notice = "plots not drawn: no pipe for the plotting script (too many open files?)";
    return false;
  }
  // What gplan printed comes before what the script prints.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t pid = spawn({python, "-", csv, out_dir}, script.read, -1, -1);
  script.close_read();
  if (pid < 0) {
    *notice = "plots not drawn: " + python + " could not be started";
    return false;
  }
  const bool sent = write_to_pipe(script.write, script_bytes, size);
  script.close_write();
  const int code = wait_for(pid);
  if (code == 0 && sent) return true;
  if (code == 0) {
    *notice = "plots not drawn: " + python + " did not read the plotting script";
  } else if (code < 0) {
    *notice = std::string("plots not drawn: ") + name + " (run by " + python +
              ") ended by signal " + std::to_string(-code);
  } else {
    *notice = std::string("plots not drawn: ") + name + " (run by " + python +
              ") exited with code " + std::to_string(code) +
              (code == 2   ? " (the CSV is not one gplan-bench wrote)"
               : code == 1 ? " (an output could not be written)"
                           : "");
  }
  return false;
}

}  // namespace

bool draw_bench_plots(const std::string& csv, const std::string& out_dir, std::string* notice) {
  return run_plot_script("plot_bench.py", kPlotBenchScript, kPlotBenchScriptSize, csv, out_dir,
                         notice);
}

bool draw_error_time_plots(const std::string& csv, const std::string& out_dir,
                           std::string* notice) {
  return run_plot_script("plot_error_time.py", kPlotErrorTimeScript, kPlotErrorTimeScriptSize, csv,
                         out_dir, notice);
}

bool draw_broad_phase_plots(const std::string& csv, const std::string& out_dir,
                            std::string* notice) {
  return run_plot_script("plot_broad_phase.py", kPlotBroadPhaseScript, kPlotBroadPhaseScriptSize,
                         csv, out_dir, notice);
}

}  // namespace gplan

#include "apps/hostile/guarded_run.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace gplanner::hostile {
namespace {

std::vector<std::string> gplan_command() {
  const char* custom = std::getenv("GPLANNER_GPLAN");
  if (!(custom && *custom)) return {GPLAN_EXECUTABLE};
  std::vector<std::string> words;
  std::istringstream in(custom);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

std::string head_of(const std::string& path, std::size_t* size) {
  std::error_code error;
  *size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  std::string text(std::min<std::size_t>(error ? 0 : *size, 1u << 20), '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  return text;
}

}  // namespace

GuardedRun run_gplan_guarded(const std::vector<std::string>& arguments, const std::string& folder,
                             double limit_s, int as_user) {
  std::vector<std::string> words = gplan_command();
  words.insert(words.end(), arguments.begin(), arguments.end());
  // Captured output lives beside the folder, not in it: the folder's entries are
  // compared before and after.
  const std::string capture = folder + ".capture";
  std::filesystem::create_directories(capture);
  const std::string out_file = capture + "/stdout", err_file = capture + "/stderr";

  GuardedRun run;
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child == 0) {
    setpgid(0, 0);
    const rlimit memory{4ull << 30, 4ull << 30};
    setrlimit(RLIMIT_AS, &memory);
    const rlimit file_size{256ull << 20, 256ull << 20};
    setrlimit(RLIMIT_FSIZE, &file_size);
    signal(SIGXFSZ, SIG_DFL);
    const int in = open("/dev/null", O_RDONLY);
    const int out = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (as_user > 0 && (setgid(as_user) != 0 || setuid(as_user) != 0)) _exit(121);
    if (chdir(folder.c_str()) != 0) _exit(120);
    dup2(in, 0);
    dup2(out, 1);
    dup2(err, 2);
    std::vector<char*> argv;
    for (std::string& word : words) argv.push_back(word.data());
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  setpgid(child, child);
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(child, &status, WNOHANG);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == child) break;
    if (run.seconds > limit_s) {
      run.hung = true;
      kill(-child, SIGKILL);
      waitpid(child, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(run.seconds < 1 ? 2 : 20));
  }
  if (!run.hung) {
    if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  }
  std::size_t out_bytes = 0;
  run.out = head_of(out_file, &out_bytes);
  run.err = head_of(err_file, &run.err_bytes);
  std::error_code ignored;
  std::filesystem::remove_all(capture, ignored);
  return run;
}

}  // namespace gplanner::hostile

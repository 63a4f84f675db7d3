#pragma once
// Runs the gplan program in a folder with a wall-clock guard: a run that does not end
// within its limit is killed (with everything it started) and reported as a hang.
// Address space and file size are capped so that a run that reads /dev/zero whole or
// writes without end fails in the child instead of taking the machine.

#include <string>
#include <vector>

namespace gplanner::hostile {

struct GuardedRun {
  bool hung = false;        // killed at the limit
  int exit_code = -1;       // when it exited
  int signal = 0;           // when a signal ended it (a crash)
  double seconds = 0;       // wall-clock time
  std::string out, err;     // standard output and error (the first MiB of each)
  std::size_t err_bytes = 0;  // standard error's whole size
};

// gplan (GPLAN_EXECUTABLE, or $GPLANNER_GPLAN split at spaces) with `arguments`, run in
// `folder` with standard input from /dev/null; with `as_user` > 0, as that user (and
// group), so that permissions hold where the tests run as root.
GuardedRun run_gplan_guarded(const std::vector<std::string>& arguments, const std::string& folder,
                             double limit_s, int as_user = 0);

}  // namespace gplanner::hostile

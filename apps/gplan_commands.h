#pragma once
// gplan's commands, dispatched by name: the whole program but for reporting errors
// (apps/gplan.cpp's main), so that tests and the command-line fuzzer can run it in
// the process.

namespace gplan {

// The usage text main prints after a UsageError.
extern const char* const kUsage;

// Runs `gplan argv[1] ...` and returns its exit code; bad usage throws UsageError, bad
// input gplanner::InputError, anything else another exception (main reports them).
int run_command(int argc, char** argv);

}  // namespace gplan

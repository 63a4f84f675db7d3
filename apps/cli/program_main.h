#pragma once
// The main of every gplanner program (gplan, gplan-bench): runs one command, reports its
// errors on stderr with the program's name and exit code (usage 2, input 2, anything
// else 1), flushes what it wrote and leaves the NVIDIA driver's teardown to a child.

namespace gplan {

// Runs `command(argc, argv)` and ends the process with its exit code; a UsageError is
// printed followed by `usage`. Never returns.
[[noreturn]] void program_main(const char* program, const char* usage, int argc, char** argv,
                               int (*command)(int, char**));

}  // namespace gplan

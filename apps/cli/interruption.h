#pragma once
// SIGINT, SIGTERM and SIGHUP end a gplan run cleanly: the handler only records the
// signal; the run polls interrupted() between stages (the planner through
// PlanOptions::should_stop), writes nothing more, says so and exits 128 + the signal
// number (130, 143, 129). A second signal ends the process at once, as it would without
// the handler.

#include <string>
#include <vector>

namespace gplan {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP (once per process).
void catch_interruptions();

// Whether SIGINT, SIGTERM or SIGHUP has arrived since catch_interruptions.
bool interrupted();

// Prints the one line saying the run was interrupted, which outputs were written
// (`written`) and which were left as they were (`left`), and returns the exit code
// (128 + the signal number).
int report_interruption(const std::vector<std::string>& written,
                        const std::vector<std::string>& left);

}  // namespace gplan

#pragma once
// What the harness's tests share beside tests/test_support.h.

#include <string>

#include "test_support.h"

namespace gplanner::testing {

// Runs the gplan-bench program built beside the tests with `arguments` (shell syntax);
// where $GPLANNER_GPLAN_BENCH is set, that command line instead (e.g. ".gpu/run
// .gpu/bin/gplan-bench").
inline CommandResult run_gplan_bench(const std::string& arguments) {
  return run_program("GPLANNER_GPLAN_BENCH", GPLAN_BENCH_EXECUTABLE, arguments);
}

}  // namespace gplanner::testing

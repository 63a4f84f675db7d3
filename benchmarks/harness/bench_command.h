#pragma once
// gplan-bench: the benchmark program (the harness of benchmarks/harness/).

namespace gplan {

// The usage text printed for --help and after a UsageError.
extern const char* const kBenchUsage;

// `gplan-bench CONFIG ...`: regression runs and the seed's tables (see kBenchUsage).
// Returns the exit code; bad usage throws UsageError, bad input gplanner::InputError.
int run_bench(int argc, char** argv);

}  // namespace gplan

// gplan-bench: the benchmark program (benchmarks/README.md); `gplan-bench` runs it.

#include "harness/bench_command.h"
#include "program_main.h"

int main(int argc, char** argv) {
  gplan::program_main("gplan-bench", gplan::kBenchUsage, argc, argv, gplan::run_bench);
}

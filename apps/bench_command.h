#pragma once

namespace gplan {

// `gplan bench CONFIG ...`: regression runs and the seed's tables (see kUsage).
int run_bench(int argc, char** argv);

}  // namespace gplan

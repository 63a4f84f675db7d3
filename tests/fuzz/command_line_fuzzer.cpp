// libFuzzer entry: the bytes as gplan's command line (see fuzz_targets.h).
#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gplanner::fuzz::command_line(data, size);
  return 0;
}

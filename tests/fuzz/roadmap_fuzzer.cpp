// libFuzzer entry: the bytes as a roadmap file (see fuzz_targets.h).
#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gplanner::fuzz::roadmap_file(data, size);
  return 0;
}

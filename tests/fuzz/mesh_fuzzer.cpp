// libFuzzer entry: the bytes as a triangle soup (see fuzz_targets.h).
#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gplanner::fuzz::triangle_soup(data, size);
  return 0;
}

// prefault_for_writing: maps pages ahead of their writes without changing what they hold.

#include "gplanner/common/prefault.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace gplanner {
namespace {

// A buffer of 24 MB (above the least size that is prefaulted), written in a pattern,
// prefaulted over an unaligned part (and over all of it), holds the same pattern after.
TEST(Prefault, KeepsWhatThePagesHold) {
  const std::size_t words = std::size_t(6) << 20;
  std::vector<std::uint32_t> buffer(words);
  for (std::size_t i = 0; i < words; ++i) buffer[i] = static_cast<std::uint32_t>(i * 2654435761u);
  prefault_for_writing(reinterpret_cast<char*>(buffer.data()) + 1001, words * 4 - 5000);
  prefault_for_writing(buffer.data(), words * 4);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < words; ++i)
    changed += buffer[i] != static_cast<std::uint32_t>(i * 2654435761u);
  EXPECT_EQ(changed, 0u);
}

// Memory reserved but not yet written (a vector's capacity): prefaulted, then written
// as usual; and ranges too small to matter, empty or null, do nothing.
TEST(Prefault, ReservedCapacityThenWritten) {
  std::vector<std::uint64_t> v;
  v.reserve(std::size_t(4) << 20);  // 32 MB
  v.push_back(7);
  prefault_for_writing(v.data() + v.size(), (v.capacity() - v.size()) * sizeof(std::uint64_t));
  EXPECT_EQ(v[0], 7u);
  for (std::uint64_t i = 1; i < (std::uint64_t(4) << 20); ++i) v.push_back(i * 3);
  EXPECT_EQ(v.back(), ((std::uint64_t(4) << 20) - 1) * 3);
  std::uint64_t small[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  prefault_for_writing(small, sizeof(small));
  EXPECT_EQ(small[7], 8u);
  prefault_for_writing(nullptr, 0);
  prefault_for_writing(small, 0);
}

}  // namespace
}  // namespace gplanner

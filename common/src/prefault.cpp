#include "gplanner/common/prefault.h"

#include <cstdint>

#include "gplanner/common/parallel_for.h"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14's; older headers lack it
#endif
#endif

namespace gplanner {

void prefault_for_writing(void* begin, std::size_t bytes) {
#if defined(__linux__)
  // Parts of 1 MB: each a call of its own, handed out to the threads as they free up.
  constexpr std::size_t kPart = std::size_t(1) << 20;
  constexpr std::size_t kLeast = 4 * kPart;  // below this, one thread's faults cost little
  const long page_size = sysconf(_SC_PAGESIZE);
  if (page_size <= 0 || bytes < kLeast) return;
  const auto page = static_cast<std::uintptr_t>(page_size);
  const auto start = reinterpret_cast<std::uintptr_t>(begin);
  const std::uintptr_t first = (start + page - 1) / page * page;
  const std::uintptr_t last = (start + bytes) / page * page;
  if (last <= first) return;
  const std::size_t parts = (last - first + kPart - 1) / kPart;
  parallel_for(
      parts, resolve_thread_count(0),
      [&](std::size_t lo, std::size_t hi, int) {
        for (std::size_t i = lo; i < hi; ++i) {
          const std::uintptr_t from = first + i * kPart;
          const std::uintptr_t to = from + kPart < last ? from + kPart : last;
          // A failure (EINVAL before Linux 5.14, ENOMEM) leaves the pages to fault as
          // they are written, which is all this could have spared.
          madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);
        }
      },
      1);
#else
  (void)begin;
  (void)bytes;
#endif
}

}  // namespace gplanner

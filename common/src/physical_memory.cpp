#include "gplanner/common/physical_memory.h"

#include <unistd.h>

#include <cstdio>

namespace gplanner {

std::size_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page_size);
}

bool fits_in_memory(double bytes) {
  const std::size_t physical = physical_memory_bytes();
  return physical == 0 || bytes <= kMemoryFractionForOneRun * static_cast<double>(physical);
}

std::string memory_text(double bytes) {
  char text[64];
  if (bytes < 1e9) {
    std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
  } else {
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  }
  return text;
}

}  // namespace gplanner

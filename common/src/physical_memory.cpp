#include "gplanner/common/physical_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

namespace gplanner {
namespace {

// The memory limit of the process's control group (a container's), or 0 where there is
// none: cgroup v2's memory.max for the group /proc/self/cgroup names, else v1's
// memory.limit_in_bytes for its memory group (each also at the mount's root, as a
// container sees its own group).
std::size_t control_group_limit() {
  std::string group, memory_group;
  std::ifstream cgroups("/proc/self/cgroup");
  for (std::string line; std::getline(cgroups, line);) {
    if (line.rfind("0::", 0) == 0) group = line.substr(3);
    const std::size_t memory = line.find(":memory:");
    if (memory != std::string::npos) memory_group = line.substr(memory + 8);
  }
  for (const std::string& file :
       {"/sys/fs/cgroup" + group + "/memory.max", std::string("/sys/fs/cgroup/memory.max"),
        "/sys/fs/cgroup/memory" + memory_group + "/memory.limit_in_bytes",
        std::string("/sys/fs/cgroup/memory/memory.limit_in_bytes")}) {
    std::ifstream in(file);
    std::string text;
    if (!(in >> text) || text == "max") continue;
    try {
      const unsigned long long limit = std::stoull(text);
      if (limit > 0 && limit < (1ULL << 60)) return static_cast<std::size_t>(limit);
    } catch (const std::exception&) {
    }
  }
  return 0;
}

}  // namespace

std::size_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  const std::size_t physical =
      static_cast<std::size_t>(pages) * static_cast<std::size_t>(page_size);
  const std::size_t limit = control_group_limit();
  return limit > 0 && limit < physical ? limit : physical;
}

std::size_t address_space_limit_bytes() {
  struct rlimit address_space {};
  if (getrlimit(RLIMIT_AS, &address_space) != 0 || address_space.rlim_cur == RLIM_INFINITY)
    return 0;
  return static_cast<std::size_t>(address_space.rlim_cur);
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

#pragma once
// The machine's physical memory, for estimates made before allocating: a run whose
// settings would need more than a stated fraction of it is refused up front (with the
// setting to change) instead of being killed, or swapping, part way.

#include <cstddef>
#include <string>

namespace gplanner {

// Bytes of physical memory (sysconf), or the control group's (a container's) memory
// limit where that is lower; 0 where the system does not say.
std::size_t physical_memory_bytes();

// The process's address-space limit (ulimit -v, RLIMIT_AS), or 0 where none is set: what
// one allocation, however brief, cannot exceed.
std::size_t address_space_limit_bytes();

// The share of physical memory one run's large buffers may take: half, leaving the
// rest to the system, the collision model and the other buffers of the run.
inline constexpr double kMemoryFractionForOneRun = 0.5;

// Whether `bytes` fits within kMemoryFractionForOneRun of physical memory (true where
// the system does not say how much there is).
bool fits_in_memory(double bytes);

// `bytes` in the unit that reads best: "512 MB", "3.2 GB".
std::string memory_text(double bytes);

}  // namespace gplanner

#pragma once
// Pages mapped ahead of their first writes, on the host's threads. A page's first write
// costs the system a fault: about 2 us on a virtual machine (the H200 host's and CI's),
// so that appending the 420,000 edges (6.7 MB) of a roadmap's round of 32,000 new
// milestones took 6.6 ms on one thread there. Faults taken on 16 threads at once took a
// seventh of the time.

#include <cstddef>

namespace gplanner {

// Maps in the pages wholly within [begin, begin + bytes), writable, without changing
// what they hold (Linux's MADV_POPULATE_WRITE), in parts on the host's threads: memory a
// caller owns and is about to write (a vector's reserved capacity). Below a few
// megabytes, or where the system cannot (a kernel before Linux 5.14, another system),
// does nothing: the writes then fault as they would have. (Since 0.5.7.)
void prefault_for_writing(void* begin, std::size_t bytes);

}  // namespace gplanner

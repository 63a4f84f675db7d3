#pragma once
// Writing to a pipe whose reader may have gone (a plot script that exited, a worker that
// ended) without gplan-bench ending by SIGPIPE.

#include <cstddef>

namespace gplan {

// Writes all of `size` bytes at `data` to `fd`; false when the reader went away (EPIPE)
// or on an error. SIGPIPE is held back in this thread meanwhile, and one it raised is
// taken away.
bool write_to_pipe(int fd, const void* data, std::size_t size);

}  // namespace gplan

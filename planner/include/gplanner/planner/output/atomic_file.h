#pragma once
// Output files written whole or not at all: the content goes to a temporary file in
// the same folder, which replaces the target only once it is complete and flushed.

#include <functional>
#include <ostream>
#include <string>

namespace gplanner {

// Calls write(stream) on a temporary file beside `path`, then renames it over `path`.
// On any failure (the writer throws, the disk fills) the temporary file is removed,
// whatever was at `path` stays untouched, and std::runtime_error says why.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace gplanner

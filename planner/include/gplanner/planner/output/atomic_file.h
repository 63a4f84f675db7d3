#pragma once
// Output files written whole or not at all: the content goes to a temporary file in
// the same folder, which replaces the target only once it is complete and flushed.

#include <functional>
#include <ostream>
#include <string>

namespace gplanner {

// Calls write(stream) on a temporary file beside `path`, then renames it over `path`.
// A symbolic link is written through: its target is replaced, the link kept. A file
// replaced keeps its permission bits (and owner, where we may give it). A `path` that
// is a folder, device, FIFO or socket, or in a folder that does not exist or take new
// files, is refused with OutputPathError (see output_paths.h) before anything is
// written. On any failure (the writer throws, the disk fills) the temporary file is
// removed, whatever was at `path` stays untouched, and std::runtime_error says why.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace gplanner

#pragma once
// The one error type for bad input: it names the file, the line where known, the key
// or element at fault, and what to change.

#include <stdexcept>
#include <string>

namespace gplanner {

// Where in an input file something was read from.
struct SourceLocation {
  std::string file;
  int line = 0;     // 1-based; 0 when unknown
  std::string key;  // YAML key path ("robot.urdf"), URDF element, ...
};

class InputError : public std::runtime_error {
 public:
  // Message: "FILE:LINE: KEY: PROBLEM" (LINE and KEY left out when unknown), one line
  // of at most a few hundred characters: control characters and terminal escapes are
  // shown escaped (\n, \x1b), and the file, the key, each quoted value ('...') and the
  // problem are cut to an excerpt ending "... (N bytes)" where longer.
  InputError(const SourceLocation& where, const std::string& problem);

  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

}  // namespace gplanner

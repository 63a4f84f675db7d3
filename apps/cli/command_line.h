#pragma once
// Parsing of `gplan SUBCOMMAND ...` arguments: positionals, --flag and --option VALUE.

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace gplan {

// Bad command-line usage; main prints it with the subcommand's usage and exits 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CommandLine {
 public:
  // Parses argv[first..argc); `options` take a value, `flags` do not.
  CommandLine(int argc, char** argv, int first, const std::set<std::string>& options,
              const std::set<std::string>& flags);

  const std::vector<std::string>& positionals() const { return positionals_; }
  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string text(const std::string& name, const std::string& fallback) const;
  // A whole number in [low, high] (decimal digits only: no sign, no wrap past the
  // range); otherwise a UsageError naming the option, the value and the range.
  unsigned long long count(const std::string& name, unsigned long long fallback,
                           unsigned long long low, unsigned long long high) const;
  // Positive finite numbers, rejected with a UsageError naming the option otherwise.
  double positive_number(const std::string& name, double fallback) const;
  // --device N|all: a CUDA device number (among those the process sees), or -1 for
  // "all" (GpuCheckerOptions::kAllDevices); `fallback` when not given.
  int gpu_device(int fallback) const;

 private:
  std::vector<std::string> positionals_;
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

// An argument as shown in a message: its first 40 characters, and its length where it
// is longer.
std::string excerpt(const std::string& text);

}  // namespace gplan

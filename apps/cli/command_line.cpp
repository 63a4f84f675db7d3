#include "command_line.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace gplan {

std::string excerpt(const std::string& text) {
  if (text.size() <= 40) return text;
  return text.substr(0, 40) + "... (" + std::to_string(text.size()) + " bytes)";
}

CommandLine::CommandLine(int argc, char** argv, int first, const std::set<std::string>& options,
                         const std::set<std::string>& flags) {
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0 || arg == "--") {
      positionals_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(2);
    std::string value;
    const std::size_t equals = name.find('=');
    const bool inline_value = equals != std::string::npos;
    if (inline_value) {
      value = name.substr(equals + 1);
      name = name.substr(0, equals);
    }
    const std::string option = "--" + excerpt(name);
    if (flags.count(name)) {
      if (inline_value)
        throw UsageError(option + " takes no value; remove '=" + excerpt(value) + "'");
      flags_.insert(name);
    } else if (options.count(name)) {
      if (!inline_value) {
        if (i + 1 >= argc)
          throw UsageError(option + " needs a value; give it as " + option + " VALUE");
        value = argv[++i];
      }
      // A second value would silently win over the first: which one was meant?
      if (values_.count(name)) throw UsageError(option + " given twice; give it once");
      values_[name] = value;
    } else {
      throw UsageError("unknown option " + option + "; use one of those listed below");
    }
  }
}

std::string CommandLine::text(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

unsigned long long CommandLine::count(const std::string& name, unsigned long long fallback,
                                      unsigned long long low, unsigned long long high) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  const std::string& text = it->second;
  errno = 0;
  unsigned long long value = 0;
  const bool digits =
      !text.empty() && text.size() <= 20 &&
      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits) value = std::strtoull(text.c_str(), nullptr, 10);
  if (!digits || errno != 0 || value < low || value > high) {
    throw UsageError("--" + name + " expects a whole number from " + std::to_string(low) + " to " +
                     std::to_string(high) + ", not '" + excerpt(text) + "'");
  }
  return value;
}

double CommandLine::positive_number(const std::string& name, double fallback) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return fallback;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || errno != 0 || !(value > 0) || !std::isfinite(value)) {
    throw UsageError("--" + name + " expects a positive number, not '" + excerpt(it->second) + "'");
  }
  return value;
}

int CommandLine::gpu_device(int fallback) const {
  const auto it = values_.find("device");
  if (it == values_.end()) return fallback;
  if (it->second == "all") return -1;
  if (it->second.empty() || it->second.size() > 4 ||
      it->second.find_first_not_of("0123456789") != std::string::npos) {
    throw UsageError("--device expects a CUDA device number (0, 1, ...) or all, not '" +
                     excerpt(it->second) + "'");
  }
  return std::stoi(it->second);
}

}  // namespace gplan

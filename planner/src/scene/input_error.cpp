#include "gplanner/planner/scene/input_error.h"

namespace gplanner {
namespace {

std::string format_message(const SourceLocation& where, const std::string& problem) {
  std::string message = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) message += ":" + std::to_string(where.line);
  message += ": ";
  if (!where.key.empty()) message += where.key + ": ";
  return message + problem;
}

}  // namespace

InputError::InputError(const SourceLocation& where, const std::string& problem)
    : std::runtime_error(format_message(where, problem)), where_(where) {}

}  // namespace gplanner

#pragma once
// A report's JSON object as the one line --json prints: invalid UTF-8 in names from the
// input becomes U+FFFD (JSON text is UTF-8), as gplanner::json_string does.

#include <nlohmann/json.hpp>

#include <string>

namespace gplan {

inline std::string json_line(const nlohmann::ordered_json& object) {
  return object.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace gplan

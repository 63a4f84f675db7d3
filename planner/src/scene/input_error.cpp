#include "gplanner/planner/scene/input_error.h"

#include <cctype>
#include <cstdio>

namespace gplanner {
namespace {

// The longest a file name, key or quoted value is echoed, and the longest problem.
constexpr std::size_t kFileExcerpt = 200;
constexpr std::size_t kKeyExcerpt = 120;
constexpr std::size_t kQuotedExcerpt = 80;
constexpr std::size_t kProblemExcerpt = 400;

// `text` with control characters and bytes a terminal would act on written as \n, \t,
// \xHH: input echoed in a message can neither break the line nor drive the terminal.
std::string escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (byte < 0x20 || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", byte);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

// The first `limit` bytes of `text` and "... (N bytes)" when it is longer (never cutting
// a UTF-8 character in two).
std::string excerpt(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return text;
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) --cut;
  return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " bytes)";
}

// A problem longer than `limit`: its beginning and its last `tail` bytes (where the
// advice is), the middle replaced by "... (N bytes left out) ...".
std::string head_and_tail(const std::string& text, std::size_t limit, std::size_t tail) {
  if (text.size() <= limit) return text;
  std::size_t head = limit - tail, from = text.size() - tail;
  while (head > 0 && (static_cast<unsigned char>(text[head]) & 0xc0) == 0x80) --head;
  while (from < text.size() && (static_cast<unsigned char>(text[from]) & 0xc0) == 0x80) ++from;
  return text.substr(0, head) + "... (" + std::to_string(from - head) + " bytes left out) ..." +
         text.substr(from);
}

bool is_word_character(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// `problem` with each quoted value ('...', an opening quote after no letter, a closing
// one before none, so that "joint's" is no quote) cut to an excerpt: messages echo
// values from the input, which may be megabytes long.
std::string shorten_quoted(const std::string& problem) {
  std::string out;
  std::size_t at = 0;
  while (at < problem.size()) {
    std::size_t open = problem.find('\'', at);
    while (open != std::string::npos && open > 0 && is_word_character(problem[open - 1])) {
      open = problem.find('\'', open + 1);
    }
    std::size_t close = open == std::string::npos ? open : problem.find('\'', open + 1);
    while (close != std::string::npos && close + 1 < problem.size() &&
           is_word_character(problem[close + 1])) {
      close = problem.find('\'', close + 1);
    }
    if (close == std::string::npos) {
      out += problem.substr(at);
      break;
    }
    out += problem.substr(at, open + 1 - at);
    out += excerpt(problem.substr(open + 1, close - open - 1), kQuotedExcerpt) + "'";
    at = close + 1;
  }
  return out;
}

std::string format_message(const SourceLocation& where, const std::string& problem) {
  std::string message =
      where.file.empty() ? std::string("<input>") : excerpt(escaped(where.file), kFileExcerpt);
  if (where.line > 0) message += ":" + std::to_string(where.line);
  message += ": ";
  if (!where.key.empty()) message += excerpt(escaped(where.key), kKeyExcerpt) + ": ";
  return message + head_and_tail(shorten_quoted(escaped(problem)), kProblemExcerpt, 100);
}

}  // namespace

InputError::InputError(const SourceLocation& where, const std::string& problem)
    : std::runtime_error(format_message(where, problem)), where_(where) {}

}  // namespace gplanner

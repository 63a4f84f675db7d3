#include "gplanner/planner/output/text_escaping.h"

#include <cstdint>
#include <cstdio>

namespace gplanner {
namespace {

constexpr char32_t kInvalid = 0xFFFFFFFF;
constexpr const char* kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// The code point starting at text[*at] (advancing *at past it), or kInvalid for a byte
// that does not start a well-formed UTF-8 sequence (*at advanced by one byte): overlong
// forms, surrogates and values above U+10FFFF are invalid too.
char32_t next_code_point(std::string_view text, std::size_t* at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(*at);
  int length = 0;
  char32_t code = 0;
  if (lead < 0x80) {
    ++*at;
    return lead;
  } else if ((lead & 0xE0) == 0xC0) {
    length = 2;
    code = lead & 0x1F;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3;
    code = lead & 0x0F;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4;
    code = lead & 0x07;
  } else {
    ++*at;
    return kInvalid;
  }
  if (*at + length > text.size()) {
    ++*at;
    return kInvalid;
  }
  for (int k = 1; k < length; ++k) {
    if ((byte(*at + k) & 0xC0) != 0x80) {
      ++*at;
      return kInvalid;
    }
    code = (code << 6) | (byte(*at + k) & 0x3F);
  }
  static constexpr char32_t kSmallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < kSmallest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
    ++*at;
    return kInvalid;
  }
  *at += length;
  return code;
}

std::string hex(const char* prefix, unsigned value, int digits) {
  char buffer[16];
  std::snprintf(buffer, sizeof(buffer), "%s%0*x", prefix, digits, value);
  return buffer;
}

// C0 controls, DEL and C1 controls.
bool is_control(char32_t c) { return c < 0x20 || (c >= 0x7F && c <= 0x9F); }

// Line and paragraph separators, and the marks that reorder text (bidirectional
// overrides and isolates) or hide at the start of it (the byte order mark).
bool is_invisible_format(char32_t c) {
  return c == 0x2028 || c == 0x2029 || (c >= 0x202A && c <= 0x202E) ||
         (c >= 0x2066 && c <= 0x2069) || c == 0xFEFF;
}

bool is_plain_yaml_word(std::string_view text) {
  if (text.empty()) return false;
  const char first = text[0];
  if (!((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z') || first == '_'))
    return false;
  for (const char c : text) {
    const bool word = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '.' || c == '-' || c == '/';
    if (!word) return false;
  }
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  for (const char* reserved : {"true", "false", "yes", "no", "on", "off", "null"})
    if (lower == reserved) return false;
  return true;
}

}  // namespace

std::string xml_escaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t begin = at;
    const char32_t c = next_code_point(text, &at);
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default: {
        const bool allowed = c != kInvalid && (c >= 0x20 || c == '\t' || c == '\n' || c == '\r') &&
                             c != 0xFFFE && c != 0xFFFF;
        if (allowed) {
          out.append(text.substr(begin, at - begin));
        } else {
          out += kReplacement;
        }
      }
    }
  }
  return out;
}

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t begin = at;
    const char32_t c = next_code_point(text, &at);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == kInvalid) {
      out += kReplacement;
    } else if (c < 0x20 || c == 0x7F) {
      out += hex("\\u", c, 4);
    } else {
      out.append(text.substr(begin, at - begin));
    }
  }
  return out + "\"";
}

std::string yaml_scalar(std::string_view text) {
  if (is_plain_yaml_word(text)) return std::string(text);
  std::string out = "\"";
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t begin = at;
    const char32_t c = next_code_point(text, &at);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      case kInvalid:
        out += kReplacement;
        break;
      default:
        if (is_control(c) || is_invisible_format(c) || c == 0xFFFE || c == 0xFFFF) {
          out += c <= 0xFF ? hex("\\x", c, 2) : hex("\\u", c, 4);
        } else {
          out.append(text.substr(begin, at - begin));
        }
    }
  }
  return out + "\"";
}

std::string terminal_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t begin = at;
    const char32_t c = next_code_point(text, &at);
    if (c == kInvalid) {
      out += hex("\\x", static_cast<unsigned char>(text[begin]), 2);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == 0x1B) {
      out += "\\e";
    } else if (c < 0x80 && is_control(c)) {
      out += hex("\\x", c, 2);
    } else if (is_control(c) || is_invisible_format(c)) {
      out += hex("\\u", c, 4);
    } else {
      out.append(text.substr(begin, at - begin));
    }
  }
  return out;
}

}  // namespace gplanner

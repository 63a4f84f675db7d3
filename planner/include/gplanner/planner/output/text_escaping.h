#pragma once
// Text taken from input (scene and file names, link and joint names) made safe for the
// format it is written in: XML (the SVG picture), YAML (the path file), JSON (--json)
// and the terminal. Bytes that are not UTF-8 become U+FFFD (or \xNN on the terminal).

#include <string>
#include <string_view>

namespace gplanner {

// For XML text and attribute values: & < > " ' as entities; characters XML 1.0 does
// not allow (control characters but tab, newline and carriage return) and invalid
// UTF-8 as U+FFFD.
std::string xml_escaped(std::string_view text);

// A YAML scalar that reads back as exactly `text` (a string): as written where it is
// plain and cannot be read as anything else (a word of letters, digits and _ . - /,
// starting with a letter or _, not true/false/yes/no/on/off/null), otherwise
// double-quoted with \" \\ and control characters escaped. Invalid UTF-8 bytes
// become U+FFFD.
std::string yaml_scalar(std::string_view text);

// A JSON string literal (quoted) that reads back as `text`: " and \\ escaped, control
// characters as \uNNNN, invalid UTF-8 bytes as U+FFFD (JSON text is UTF-8).
std::string json_string(std::string_view text);

// For the terminal: control characters (C0, DEL and C1, escape sequences among them)
// and invalid UTF-8 bytes shown as \n, \t, \r, \e or \xNN instead of sent raw.
std::string terminal_text(std::string_view text);

}  // namespace gplanner

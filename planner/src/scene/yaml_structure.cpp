#include "gplanner/planner/scene/yaml_structure.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <map>
#include <sstream>
#include <vector>

#include "gplanner/planner/scene/input_error.h"

namespace gplanner {
namespace {

// Walks the events of one document, keeping the open maps and lists, the key path, the
// nodes the document expands to and the size of each anchored node.
class StructureChecker : public YAML::EventHandler {
 public:
  StructureChecker(std::string path, std::string settings_key)
      : path_(std::move(path)), settings_key_(std::move(settings_key)) {}

  int document_line = 0;  // where the document starts, 1-based

  void OnDocumentStart(const YAML::Mark& mark) override { document_line = mark.line + 1; }
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    node(mark, anchor, "");
    record_anchor(anchor, 1);
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const std::string key = node(mark, 0, "");
    if (in_settings()) refuse_in_settings(mark, key);
    const std::uint64_t size = anchor < anchor_sizes_.size() ? anchor_sizes_[anchor] : 1;
    expanded_ += size - 1;  // node() counted one
    if (expanded_ > kMaxExpandedYamlNodes) {
      throw InputError({path_, mark.line + 1, key},
                       "aliases (*) expand the file to more than " +
                           std::to_string(kMaxExpandedYamlNodes) +
                           " nodes; write the repeated parts out, or repeat them less");
    }
  }

  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                const std::string& value) override {
    node(mark, anchor, value);
    record_anchor(anchor, 1);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, false);
  }
  void OnSequenceEnd() override { close(); }

  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, true);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    bool is_map = false;
    std::string key;                    // the key path of this map or list
    std::size_t children = 0;           // nodes met in it (keys and values, for a map)
    std::string last_key;               // a map's key awaiting its value
    std::map<std::string, int> lines;   // a map's keys and their lines
    std::uint64_t expanded_at_start = 0;
    YAML::anchor_t anchor = 0;
    bool settings = false;              // the settings map or within it
  };

  static std::string join(const std::string& key, const std::string& name) {
    return key.empty() ? name : key + "." + name;
  }

  bool in_settings() const { return !frames_.empty() && frames_.back().settings; }

  // Whether the node now starting is the value of the top-level settings key.
  bool is_settings_value() const {
    return frames_.size() == 1 && frames_[0].is_map && frames_[0].children % 2 == 1 &&
           frames_[0].last_key == settings_key_;
  }

  [[noreturn]] void refuse_in_settings(const YAML::Mark& mark, const std::string& key) const {
    throw InputError({path_, mark.line + 1, key},
                     "anchors (&) and aliases (*) are not allowed in " + settings_key_ +
                         " settings; write each value out");
  }

  // Counts a node starting at `mark` in the open map or list; returns its key path. A
  // scalar key (`scalar`) is checked against the map's other keys.
  std::string node(const YAML::Mark& mark, YAML::anchor_t anchor, const std::string& scalar) {
    ++expanded_;
    const bool settings = in_settings() || is_settings_value();
    const std::string key = key_of(mark, scalar);
    if (settings && anchor != 0) refuse_in_settings(mark, key);
    return key;
  }

  // The key path of a node starting in the open map or list, counting it there.
  std::string key_of(const YAML::Mark& mark, const std::string& scalar) {
    if (frames_.empty()) return "";
    Frame& frame = frames_.back();
    const std::size_t index = frame.children++;
    if (!frame.is_map) return frame.key + "[" + std::to_string(index) + "]";
    if (index % 2 == 1) return join(frame.key, frame.last_key);
    frame.last_key = scalar;
    const int line = mark.line + 1;
    const auto [it, added] = frame.lines.emplace(scalar, line);
    if (!added && !scalar.empty()) {
      throw InputError({path_, line, join(frame.key, scalar)},
                       "key given twice in one map (lines " + std::to_string(it->second) +
                           " and " + std::to_string(line) +
                           "); YAML keeps only one, so keep the one you mean and remove the "
                           "other");
    }
    return join(frame.key, scalar);
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool is_map) {
    const bool settings = in_settings() || is_settings_value();
    Frame frame;
    frame.key = node(mark, anchor, "");
    frame.is_map = is_map;
    frame.expanded_at_start = expanded_;
    frame.anchor = anchor;
    frame.settings = settings;
    frames_.push_back(std::move(frame));
  }

  void close() {
    const Frame& frame = frames_.back();
    record_anchor(frame.anchor, expanded_ - frame.expanded_at_start + 1);
    frames_.pop_back();
  }

  void record_anchor(YAML::anchor_t anchor, std::uint64_t size) {
    if (anchor == 0) return;
    if (anchor >= anchor_sizes_.size()) anchor_sizes_.resize(anchor + 1, 1);
    anchor_sizes_[anchor] = size;
  }

  std::string path_;
  std::string settings_key_;
  std::vector<Frame> frames_;
  std::vector<std::uint64_t> anchor_sizes_;
  std::uint64_t expanded_ = 0;
};

// The first line at or before `line` (1-based) indented with a tab, or 0.
int tab_indented_line(const std::string& text, int line) {
  std::istringstream lines(text);
  std::string row;
  for (int number = 1; number <= line && std::getline(lines, row); ++number) {
    const std::size_t first = row.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (row.find('\t') < first) return number;
  }
  return 0;
}

// Whether line `number` (1-based) of `text` holds a key longer than YAML's limit for an
// implicit key (one written without "? "), 1,024 characters: yaml-cpp then says "illegal
// map value".
bool long_implicit_key(const std::string& text, int number) {
  std::istringstream lines(text);
  std::string row;
  for (int i = 1; std::getline(lines, row); ++i) {
    if (i != number) continue;
    const std::size_t first = row.find_first_not_of(" \t-");
    const std::size_t colon = row.find(':', first == std::string::npos ? 0 : first);
    return first != std::string::npos && colon != std::string::npos && colon - first > 1024;
  }
  return false;
}

}  // namespace

void check_yaml_structure(const std::string& text, const std::string& path,
                          const std::string& settings_key) {
  std::istringstream stream(text);
  try {
    YAML::Parser parser(stream);
    StructureChecker checker(path, settings_key);
    if (!parser.HandleNextDocument(checker)) return;  // empty: the loader says what is missing
    StructureChecker second(path, settings_key);
    if (parser.HandleNextDocument(second)) {
      throw InputError({path, second.document_line, ""},
                       "holds more than one YAML document (separated by '---'); a scene file "
                       "holds one: remove the others or put them in files of their own");
    }
  } catch (const YAML::DeepRecursion& e) {
    throw InputError({path, e.mark.line + 1, "yaml"},
                     "lists or maps nested more than " + std::to_string(e.depth()) +
                         " deep; a scene needs a few levels, so remove the extra nesting");
  } catch (const YAML::ParserException& e) {
    const int line = e.mark.line + 1;
    const int tab = tab_indented_line(text, line + 1);
    if (tab > 0) {
      throw InputError({path, tab, "yaml"}, "tabs cannot indent YAML; use spaces");
    }
    if (long_implicit_key(text, line)) {
      throw InputError({path, line, "yaml"},
                       "a key longer than 1,024 characters, more than YAML allows a key written "
                       "this way; shorten it");
    }
    throw InputError({path, line, "yaml"},
                     "malformed YAML: " + e.msg +
                         "; fix the syntax here (indent with spaces, close every bracket and "
                         "quote, put a space after each ':')");
  }
}

YAML::Node load_checked_yaml(const std::string& path, const InputFileKind& kind,
                             const std::string& settings_key) {
  const std::string text = read_input_file(path, kind, {path, 0, ""});
  check_yaml_structure(text, path, settings_key);
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError({path, e.mark.line + 1, "yaml"}, "malformed YAML: " + e.msg);
  }
}

}  // namespace gplanner

// Names from input escaped for the format they are written in: XML, YAML, JSON, the
// terminal.

#include "gplanner/planner/output/text_escaping.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace gplanner {
namespace {

// Names a careless user or an attacker might give: YAML syntax, quotes, control
// characters, escape sequences, invalid UTF-8 cut out of a longer character.
const std::vector<std::string> kHostileNames = {"a: b",
                                                "#x",
                                                "\"",
                                                "\\",
                                                "line\nbreak",
                                                "- z",
                                                "*alias",
                                                "&anchor",
                                                "{",
                                                "}",
                                                "[",
                                                "!tag",
                                                "%directive",
                                                "@at",
                                                "`tick",
                                                "'single'",
                                                "? key",
                                                "|",
                                                ">",
                                                "true",
                                                "No",
                                                "null",
                                                "~",
                                                "1.5",
                                                "0x10",
                                                "",
                                                " leading",
                                                "trailing ",
                                                "tab\there",
                                                "cr\rhere",
                                                std::string("nul\0byte", 8),
                                                "\x1b[31mred\x1b[0m",
                                                "caf\xc3\xa9",
                                                "\xe2\x80\xae"
                                                "reversed",
                                                "del\x7f",
                                                "bom\xef\xbb\xbf",
                                                "x",
                                                "joint_1",
                                                "a-b.c/d"};

TEST(TextEscaping, YamlScalarsReadBackAsWritten) {
  for (const std::string& name : kHostileNames) {
    const std::string scalar = yaml_scalar(name);
    for (const std::string& document :
         {"key: " + scalar + "\n", "list: [" + scalar + ", next]\n",
          "map: {" + scalar + ": 1, other: 2}\n", "# of " + scalar + "\nkey: v\n"}) {
      YAML::Node root;
      ASSERT_NO_THROW(root = YAML::Load(document)) << document;
      if (root["key"] && document[0] == 'k') {
        EXPECT_EQ(root["key"].as<std::string>(), name) << document;
      } else if (root["list"]) {
        ASSERT_EQ(root["list"].size(), 2u) << document;
        EXPECT_EQ(root["list"][0].as<std::string>(), name) << document;
      } else if (root["map"]) {
        ASSERT_EQ(root["map"].size(), 2u) << document;
        EXPECT_EQ(root["map"][name].as<int>(), 1) << document;
      } else {
        EXPECT_EQ(root["key"].as<std::string>(), "v") << "the comment stays one line: " << document;
      }
    }
  }
}

TEST(TextEscaping, YamlKeepsPlainWordsPlain) {
  EXPECT_EQ(yaml_scalar("shoulder_pan_joint"), "shoulder_pan_joint");
  EXPECT_EQ(yaml_scalar("scenes/piano.yaml"), "scenes/piano.yaml");
  EXPECT_EQ(yaml_scalar("a: b"), "\"a: b\"");
  EXPECT_EQ(yaml_scalar("true"), "\"true\"");
  EXPECT_EQ(yaml_scalar("\xff"), "\"\xef\xbf\xbd\"") << "invalid UTF-8 becomes U+FFFD";
}

TEST(TextEscaping, XmlHasNoMarkupOrForbiddenCharactersLeft) {
  EXPECT_EQ(xml_escaped("<script>alert('x') & \"y\"</script>"),
            "&lt;script&gt;alert(&apos;x&apos;) &amp; &quot;y&quot;&lt;/script&gt;");
  EXPECT_EQ(xml_escaped(std::string("a\0b\x1b", 4)),
            "a\xef\xbf\xbd"
            "b\xef\xbf\xbd");
  EXPECT_EQ(xml_escaped("caf\xc3\xa9\n"), "caf\xc3\xa9\n");
  EXPECT_EQ(xml_escaped("\xc3"), "\xef\xbf\xbd") << "a cut UTF-8 sequence";
}

TEST(TextEscaping, TerminalTextHasNoControlCharacters) {
  EXPECT_EQ(terminal_text("\x1b]0;title\x07red\x1b[31m"), "\\e]0;title\\x07red\\e[31m");
  EXPECT_EQ(terminal_text("a\nb\tc\r"), "a\\nb\\tc\\r");
  EXPECT_EQ(terminal_text("\xc2\x9b"
                          "2J"),
            "\\u009b2J")
      << "C1 CSI";
  EXPECT_EQ(terminal_text("\xe2\x80\xae"
                          "abc"),
            "\\u202eabc")
      << "a bidirectional override";
  EXPECT_EQ(terminal_text("\xff"
                          "x"),
            "\\xffx");
  EXPECT_EQ(terminal_text("caf\xc3\xa9 / scenes/a.yaml"), "caf\xc3\xa9 / scenes/a.yaml");
  for (const std::string& name : kHostileNames) {
    for (const char c : terminal_text(name)) {
      const auto byte = static_cast<unsigned char>(c);
      EXPECT_TRUE(byte >= 0x20 && byte != 0x7f) << "a control byte left in " << terminal_text(name);
    }
  }
}

TEST(TextEscaping, JsonStringsAreValidJson) {
  EXPECT_EQ(json_string("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json_string("x\n\x1b"), "\"x\\u000a\\u001b\"");
  EXPECT_EQ(json_string("caf\xc3\xa9"), "\"caf\xc3\xa9\"");
  EXPECT_EQ(json_string("\xff"), "\"\xef\xbf\xbd\"") << "invalid UTF-8 as U+FFFD";
  for (const std::string& name : kHostileNames) {
    const std::string json = json_string(name);
    for (const char c : json) {
      const auto byte = static_cast<unsigned char>(c);
      EXPECT_TRUE(byte >= 0x20 && byte != 0x7f) << "a control byte left in " << json;
    }
    // A JSON string is a YAML double-quoted scalar: it reads back as the name (with
    // U+FFFD where the name was not UTF-8).
    const std::string back = YAML::Load(json).as<std::string>();
    EXPECT_EQ(json_string(back), json) << name;
  }
}

}  // namespace
}  // namespace gplanner

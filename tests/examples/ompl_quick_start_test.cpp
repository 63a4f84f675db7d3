// The README's OMPL program is examples/ompl_quick_start.cpp, which the build compiles:
// the README's block is contained in the file verbatim, and the program plans a
// shipped scene (cpu backend).

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.h"

namespace gplanner {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The first ```cpp block after `heading` in `markdown` ("" when there is none).
std::string cpp_block_after(const std::string& markdown, const std::string& heading) {
  const std::size_t section = markdown.find(heading);
  if (section == std::string::npos) return "";
  const std::string open = "```cpp\n";
  const std::size_t begin = markdown.find(open, section);
  if (begin == std::string::npos) return "";
  const std::size_t end = markdown.find("```", begin + open.size());
  if (end == std::string::npos) return "";
  return markdown.substr(begin + open.size(), end - begin - open.size());
}

TEST(OmplQuickStart, ReadmeBlockIsTheExample) {
  const std::string block =
      cpp_block_after(read_file(testing::project_root() + "/README.md"), "## In OMPL code");
  ASSERT_GT(block.size(), 200u) << "no ```cpp block under \"## In OMPL code\" in README.md";
  const std::string example = read_file(testing::project_root() + "/examples/ompl_quick_start.cpp");
  EXPECT_NE(example.find(block), std::string::npos)
      << "README.md's OMPL block differs from examples/ompl_quick_start.cpp; copy one "
         "into the other";
}

TEST(OmplQuickStart, PlansAShippedScene) {
  const std::string command = "'" + std::string(GPLANNER_OMPL_QUICK_START_EXECUTABLE) + "' '" +
                              testing::project_root() + "/scenes/pr2_base_arm.yaml' cpu 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[4096];
  for (std::size_t got; (got = fread(buffer, 1, sizeof(buffer), pipe)) > 0;)
    out.append(buffer, got);
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  EXPECT_NE(out.find("Solution found"), std::string::npos) << out;
}

}  // namespace
}  // namespace gplanner

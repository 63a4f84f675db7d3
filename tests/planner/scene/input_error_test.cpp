// InputError messages: one line of a few hundred characters at most, whatever the
// input echoed in them holds.

#include "gplanner/planner/scene/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace gplanner {
namespace {

TEST(InputError, FormatsFileLineKeyAndProblem) {
  EXPECT_STREQ(InputError({"a.yaml", 3, "robot.mesh"}, "missing; add it").what(),
               "a.yaml:3: robot.mesh: missing; add it");
  EXPECT_STREQ(InputError({"a.yaml", 0, ""}, "the joint's limits").what(),
               "a.yaml: the joint's limits");
}

TEST(InputError, ControlCharactersAndTerminalEscapesAreShownEscaped) {
  const std::string message =
      InputError({"a\nb.yaml", 1, "na\x1b[2Jme"}, "found 'x\ty\r\x07'").what();
  EXPECT_EQ(message, "a\\nb.yaml:1: na\\x1b[2Jme: found 'x\\ty\\r\\x07'");
}

TEST(InputError, LongEchoedValuesAreCutToAnExcerpt) {
  const std::string value(20 * 1024 * 1024, 'v');
  const std::string message =
      InputError({"a.yaml", 2, "name"}, "expected a number, found '" + value + "'").what();
  EXPECT_LT(message.size(), 300u);
  EXPECT_NE(message.find("'" + std::string(80, 'v') + "... (20971520 bytes)'"), std::string::npos)
      << message;
  const std::string long_file(5000, 'f');
  const std::string from_file = InputError({long_file, 1, std::string(5000, 'k')}, "x").what();
  EXPECT_LT(from_file.size(), 500u);
  EXPECT_NE(from_file.find("... (5000 bytes)"), std::string::npos);
  // A long problem keeps its end, where the advice is.
  const std::string long_problem =
      InputError({"a.yaml", 1, ""}, "bad [" + std::string(5000, 'p') + "]; fix the file").what();
  EXPECT_LT(long_problem.size(), 500u);
  EXPECT_EQ(long_problem.rfind("; fix the file"), long_problem.size() - 14) << long_problem;
  EXPECT_NE(long_problem.find("bytes left out"), std::string::npos) << long_problem;
}

}  // namespace
}  // namespace gplanner

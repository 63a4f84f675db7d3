// Every input of the fuzz corpora (grown by libFuzzer, tests/fuzz/corpus/TARGET/),
// replayed through the same target code: each must end normally (see fuzz_targets.h).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/fuzz_targets.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;

std::size_t replay(const std::string& target,
                   void (*run)(const std::uint8_t* data, std::size_t size)) {
  const fs::path folder = fs::path(testing::project_root()) / "tests/fuzz/corpus" / target;
  std::size_t count = 0;
  if (!fs::is_directory(folder)) return 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string bytes = testing::read_file(entry.path().string());
    SCOPED_TRACE(entry.path().string());
    run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    ++count;
  }
  return count;
}

TEST(FuzzCorpus, SceneFiles) { EXPECT_GT(replay("scene", fuzz::scene_file), 10u); }
TEST(FuzzCorpus, UrdfFiles) { EXPECT_GT(replay("urdf", fuzz::urdf_file), 10u); }
TEST(FuzzCorpus, SrdfFiles) { EXPECT_GT(replay("srdf", fuzz::srdf_file), 10u); }
TEST(FuzzCorpus, TriangleSoups) { EXPECT_GT(replay("mesh", fuzz::triangle_soup), 10u); }
TEST(FuzzCorpus, CommandLines) { EXPECT_GE(replay("command_line", fuzz::command_line), 10u); }
TEST(FuzzCorpus, RoadmapFiles) { EXPECT_GE(replay("roadmap", fuzz::roadmap_file), 5u); }

}  // namespace
}  // namespace gplanner

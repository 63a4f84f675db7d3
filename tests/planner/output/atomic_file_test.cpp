// Output files are written whole or not at all.

#include "gplanner/planner/output/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "test_support.h"

namespace gplanner {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t files_in(const std::string& folder) {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder)) ++count;
  return count;
}

TEST(AtomicFile, WritesTheWholeContent) {
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/out.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "first\nsecond\n"; });
  EXPECT_EQ(read_file(path), "first\nsecond\n");
  EXPECT_EQ(files_in(scratch.path()), 1u) << "no temporary file is left behind";
}

TEST(AtomicFile, AFailedWriteLeavesThePreviousContent) {
  testing::ScratchFolder scratch;
  const std::string path = scratch.write("out.txt", "kept\n");
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& out) {
                                       out << "half of a new file";
                                       throw std::runtime_error("the writer failed");
                                     }),
               std::runtime_error);
  EXPECT_EQ(read_file(path), "kept\n");
  EXPECT_EQ(files_in(scratch.path()), 1u) << "the temporary file is removed";
}

TEST(AtomicFile, AMissingFolderIsAnError) {
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/no/such/folder/out.txt";
  EXPECT_THROW(write_file_atomically(path, [](std::ostream& out) { out << "x"; }),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace gplanner

// Output files are written whole or not at all.

#include "gplanner/planner/output/atomic_file.h"

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gplanner/planner/output/output_paths.h"
#include "test_support.h"

namespace gplanner {
namespace {

std::size_t files_in(const std::string& folder) {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder)) ++count;
  return count;
}

TEST(AtomicFile, WritesTheWholeContent) {
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/out.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "first\nsecond\n"; });
  EXPECT_EQ(testing::read_file(path), "first\nsecond\n");
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
  EXPECT_EQ(testing::read_file(path), "kept\n");
  EXPECT_EQ(files_in(scratch.path()), 1u) << "the temporary file is removed";
}

TEST(AtomicFile, AMissingFolderIsAnError) {
  testing::ScratchFolder scratch;
  const std::string path = scratch.path() + "/no/such/folder/out.txt";
  EXPECT_THROW(write_file_atomically(path, [](std::ostream& out) { out << "x"; }),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(AtomicFile, ANonRegularTargetIsRefusedAndKept) {
  testing::ScratchFolder scratch;
  const std::string fifo = scratch.path() + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_THROW(write_file_atomically(fifo, [](std::ostream& out) { out << "x"; }), OutputPathError);
  EXPECT_EQ(std::filesystem::status(fifo).type(), std::filesystem::file_type::fifo);
  EXPECT_THROW(write_file_atomically("/dev/null", [](std::ostream& out) { out << "x"; }),
               OutputPathError);
  struct stat status {};
  ASSERT_EQ(stat("/dev/null", &status), 0);
  EXPECT_TRUE(S_ISCHR(status.st_mode));
  EXPECT_EQ(files_in(scratch.path()), 1u);
}

TEST(AtomicFile, WritesThroughASymbolicLinkKeepingPermissionBits) {
  testing::ScratchFolder scratch;
  const std::string target = scratch.write("target.txt", "old\n");
  ASSERT_EQ(chmod(target.c_str(), 0600), 0);
  const std::string link = scratch.path() + "/link.txt";
  std::filesystem::create_symlink("target.txt", link);
  write_file_atomically(link, [](std::ostream& out) { out << "new\n"; });
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(testing::read_file(target), "new\n");
  struct stat status {};
  ASSERT_EQ(stat(target.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 07777, 0600u);
  EXPECT_EQ(files_in(scratch.path()), 2u) << "no temporary file is left behind";
}

TEST(AtomicFile, ANewFileGetsTheUsualPermissionBits) {
  testing::ScratchFolder scratch;
  const mode_t mask = umask(022);
  const std::string path = scratch.path() + "/new.txt";
  write_file_atomically(path, [](std::ostream& out) { out << "x"; });
  umask(mask);
  struct stat status {};
  ASSERT_EQ(stat(path.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 07777, 0644u) << "not the temporary file's 0600";
}

}  // namespace
}  // namespace gplanner

namespace gplanner {
namespace {

// Every entry of `folder`, hidden ones included.
std::vector<std::string> entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A process killed (SIGKILL: no handler runs) in the middle of writing leaves nothing
// beside the target: no hidden temporary, the old content untouched (issue 32).
TEST(AtomicFile, AProcessKilledWhileWritingLeavesNothingBehind) {
  const testing::ScratchFolder folder;
  const std::string kept = folder.write("kept.yaml", "old content\n");
  for (const std::string& name : {std::string("new.bin"), std::string("kept.yaml")}) {
    const std::vector<std::string> before = entries(folder.path());
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      write_file_atomically(folder.path() + "/" + name, [](std::ostream& out) {
        out << std::string(1 << 20, 'x');
        out.flush();
        raise(SIGKILL);
      });
      _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGKILL);
    EXPECT_EQ(entries(folder.path()), before) << name;
  }
  EXPECT_EQ(testing::read_file(kept), "old content\n");
}

}  // namespace
}  // namespace gplanner

// Output paths are checked before any work: kinds, folders, links, inputs and other
// outputs.

#include "gplanner/planner/output/output_paths.h"

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;

// The message of the OutputPathError `check` throws ("" when it throws none).
template <typename Check>
std::string refusal(Check check) {
  try {
    check();
  } catch (const OutputPathError& e) {
    return e.what();
  }
  return "";
}

std::string refusal_of(const std::string& path) {
  return refusal([&] { writable_output_target("--out", path); });
}

TEST(OutputPaths, ANewFileInAWritableFolderIsAccepted) {
  testing::ScratchFolder scratch;
  const OutputTarget target = writable_output_target("--out", scratch.path() + "/new.yaml");
  EXPECT_FALSE(target.exists);
  EXPECT_EQ(target.path, fs::canonical(scratch.path()).string() + "/new.yaml");
}

TEST(OutputPaths, AnExistingFileKeepsItsIdentityAndPermissionBits) {
  testing::ScratchFolder scratch;
  const std::string file = scratch.write("old.yaml", "x");
  ASSERT_EQ(chmod(file.c_str(), 0604), 0);
  const OutputTarget target = writable_output_target("--out", file);
  struct stat status {};
  ASSERT_EQ(stat(file.c_str(), &status), 0);
  EXPECT_TRUE(target.exists);
  EXPECT_EQ(target.inode, status.st_ino);
  EXPECT_EQ(target.mode, 0604u);
}

TEST(OutputPaths, NonRegularFilesAreRefusedNamingOptionAndPath) {
  testing::ScratchFolder scratch;
  EXPECT_EQ(refusal_of("/dev/null").rfind("--out /dev/null: is a character device", 0), 0u)
      << refusal_of("/dev/null");
  ASSERT_EQ(mkfifo((scratch.path() + "/fifo").c_str(), 0644), 0);
  EXPECT_NE(refusal_of(scratch.path() + "/fifo").find("is a FIFO"), std::string::npos);
  EXPECT_NE(refusal_of(scratch.path()).find("is a folder"), std::string::npos);
  EXPECT_NE(refusal_of(scratch.path() + "/").find("names a folder"), std::string::npos);
  EXPECT_NE(refusal_of("").find("an empty file name"), std::string::npos);
}

TEST(OutputPaths, MissingFoldersLoopsAndLongNamesAreClearErrors) {
  testing::ScratchFolder scratch;
  EXPECT_NE(refusal_of(scratch.path() + "/no/such/out.yaml").find("does not exist"),
            std::string::npos);
  const std::string file = scratch.write("file", "x");
  EXPECT_NE(refusal_of(file + "/out.yaml").find("not a folder"), std::string::npos);
  fs::create_symlink("b", scratch.path() + "/a");
  fs::create_symlink("a", scratch.path() + "/b");
  EXPECT_NE(refusal_of(scratch.path() + "/a").find("too many symbolic links"), std::string::npos);
  EXPECT_NE(refusal_of(scratch.path() + "/a/out.yaml").find("too many symbolic links"),
            std::string::npos);
  EXPECT_NE(refusal_of(scratch.path() + "/" + std::string(300, 'n')).find("too long"),
            std::string::npos);
}

TEST(OutputPaths, LinksAreFollowedToTheirTarget) {
  testing::ScratchFolder scratch;
  fs::create_directory(scratch.path() + "/real");
  fs::create_symlink("real/new.yaml", scratch.path() + "/dangling");
  fs::create_symlink("dangling", scratch.path() + "/chain");
  const OutputTarget target = writable_output_target("--out", scratch.path() + "/chain");
  EXPECT_FALSE(target.exists);
  EXPECT_EQ(target.path, fs::canonical(scratch.path()).string() + "/real/new.yaml");
  fs::create_symlink("/dev/null", scratch.path() + "/to_device");
  EXPECT_NE(refusal_of(scratch.path() + "/to_device").find("character device"), std::string::npos);
}

TEST(OutputPaths, AReadOnlyFolderOrFileIsRefused) {
  if (geteuid() == 0) GTEST_SKIP() << "permission bits do not stop root";
  testing::ScratchFolder scratch;
  const std::string file = scratch.write("read_only.yaml", "x");
  ASSERT_EQ(chmod(file.c_str(), 0444), 0);
  EXPECT_NE(refusal_of(file).find("not writable"), std::string::npos);
  fs::create_directory(scratch.path() + "/locked");
  ASSERT_EQ(chmod((scratch.path() + "/locked").c_str(), 0555), 0);
  EXPECT_NE(refusal_of(scratch.path() + "/locked/out.yaml").find("cannot create files"),
            std::string::npos);
  chmod((scratch.path() + "/locked").c_str(), 0755);
}

TEST(OutputPaths, AnOutputIsNeverAnInputOrAnotherOutput) {
  testing::ScratchFolder scratch;
  const std::string scene = scratch.write("scene.yaml", "x");
  ASSERT_EQ(link(scene.c_str(), (scratch.path() + "/hard.yaml").c_str()), 0);
  fs::create_symlink("scene.yaml", scratch.path() + "/soft.yaml");
  const std::vector<NamedFile> inputs{{"the scene file", scene}};
  for (const std::string& name : {"scene.yaml", "hard.yaml", "soft.yaml", "./scene.yaml"}) {
    const std::string message = refusal([&] {
      check_output_paths({{"--out", scratch.path() + "/" + name}}, inputs);
    });
    EXPECT_NE(message.find("would overwrite the scene file"), std::string::npos) << name;
  }
  const std::string message = refusal([&] {
    check_output_paths(
        {{"--out", scratch.path() + "/new"}, {"--picture", scratch.path() + "/./new"}}, inputs);
  });
  EXPECT_NE(message.find("--picture " + scratch.path() + "/./new: is also --out"),
            std::string::npos)
      << message;
  EXPECT_EQ(refusal([&] {
              check_output_paths(
                  {{"--out", scratch.path() + "/a"}, {"--picture", scratch.path() + "/b"}},
                  {{"the scene file", scene}, {"missing", scratch.path() + "/m"}});
            }),
            "");
}

}  // namespace
}  // namespace gplanner

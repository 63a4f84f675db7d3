// Input files: a loader reads only a readable regular file within its kind's size
// limit, and says exactly what the path is otherwise.

#include "gplanner/planner/scene/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;

// The message check_input_file gives for `path`, or "accepted".
std::string problem_of(const std::string& path, const InputFileKind& kind = kMeshFile) {
  try {
    check_input_file(path, kind, {"scene.yaml", 3, "obstacles[0].mesh"});
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(InputFile, EachKindOfPathIsNamed) {
  testing::ScratchFolder scratch;
  const std::string folder = scratch.path();
  const std::string file = scratch.write("part.obj", "v 0 0 0\n");
  EXPECT_EQ(problem_of(file), "accepted");

  const std::string fifo = folder + "/fifo.obj";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string broken = folder + "/broken.obj";
  fs::create_symlink(folder + "/nothing.obj", broken);
  const std::string loop = folder + "/loop.obj";
  fs::create_symlink(loop, loop);
  const std::string socket_path = folder + "/socket.obj";
  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.size(), sizeof(address.sun_path));
  std::strncpy(address.sun_path, socket_path.c_str(), sizeof(address.sun_path) - 1);
  ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  close(fd);

  const struct {
    std::string path, says;
  } cases[] = {
      {folder + "/missing.obj", "does not exist"},
      {folder, "is a folder, not a file"},
      {"/dev/null", "is a device, not a file"},
      {fifo, "is a FIFO (named pipe), not a file"},
      {socket_path, "is a socket, not a file"},
      {broken, "is a broken symbolic link"},
      {loop, "is a symbolic link loop"},
      {folder + "/" + std::string(5000, 'x') + ".obj", "has a name too long"},
      {file + "/inside.obj", "part of its path is a file, not a folder"},
      {"", "is an empty name"},
  };
  for (const auto& c : cases) {
    const std::string message = problem_of(c.path);
    EXPECT_EQ(message.rfind("scene.yaml:3: obstacles[0].mesh: mesh '", 0), 0u) << message;
    EXPECT_NE(message.find(c.says), std::string::npos) << message;
    EXPECT_LT(message.size(), 500u) << message;
  }
}

TEST(InputFile, NoPermissionIsSaid) {
  if (geteuid() == 0) GTEST_SKIP() << "root reads files whatever their permissions";
  testing::ScratchFolder scratch;
  const std::string file = scratch.write("part.obj", "v 0 0 0\n");
  ASSERT_EQ(chmod(file.c_str(), 0), 0);
  EXPECT_NE(problem_of(file).find("cannot be read; check its permissions"), std::string::npos);
}

TEST(InputFile, FilesLargerThanTheirKindsLimitAreRefusedUnread) {
  testing::ScratchFolder scratch;
  const std::string file = scratch.path() + "/big.yaml";
  fs::resize_file(scratch.write("big.yaml", ""), kSceneFile.max_bytes + 1);  // sparse
  const std::string message = problem_of(file, kSceneFile);
  EXPECT_NE(message.find("is 16 MiB, more than the 16 MiB a scene file may have"),
            std::string::npos)
      << message;
  EXPECT_THROW(read_input_file(file, kSceneFile, {file, 0, ""}), InputError);
  EXPECT_EQ(problem_of(file, kMeshFile), "accepted");
}

TEST(InputFile, ReadReturnsTheWholeFileAndNamesItselfOnce) {
  testing::ScratchFolder scratch;
  const std::string file = scratch.write("scene.yaml", "name: x\n");
  EXPECT_EQ(read_input_file(file, kSceneFile, {file, 0, ""}), "name: x\n");
  try {
    read_input_file(scratch.path(), kSceneFile, {scratch.path(), 0, ""});
    FAIL() << "a folder was read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              scratch.path() + ": scene file is a folder, not a file; give the path of a scene file");
  }
}

}  // namespace
}  // namespace gplanner

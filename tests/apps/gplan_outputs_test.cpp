// gplan's output files through the real binary: every output checked before any work
// (never a device, never an input of the run or another output, symbolic links written
// through), SIGINT and SIGTERM ending a run cleanly, and the outputs left alone said so
// when no path is found.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_support.h"

extern char** environ;

namespace gplanner {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::run_gplan;
using testing::ScratchFolder;

// A one-joint arm swinging a cube (a URDF with a mesh), below a cube obstacle (a mesh):
// planned in a few hundredths of a second.
const char* const kArmUrdf = R"(<robot name="arm">
  <link name="base"/>
  <link name="hand"><collision><geometry><mesh filename="hand.obj"/></geometry></collision></link>
  <joint name="turn" type="revolute"><parent link="base"/><child link="hand"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
)";
const char* const kArmScene = R"(name: arm
robot:
  urdf: arm.urdf
  planned_joints: [turn]
obstacles:
  - mesh: box.obj
    pose: {xyz: [0, 0, 2]}
start:
  joints: {turn: -0.5}
goal:
  joints: {turn: 0.5}
)";
// A cube robot that must cross a wall spanning the bounds: no path, ever.
const char* const kWalledScene = R"(name: walled
robot:
  mesh: box.obj
obstacles:
  - box: [0.2, 10, 10]
bounds:
  min: [-2, -1.5, -1]
  max: [2, 1.5, 1]
start:
  base: {xyz: [-1.8, 0, 0], quat_wxyz: [1, 0, 0, 0]}
goal:
  base: {xyz: [1.8, 0, 0], quat_wxyz: [1, 0, 0, 0]}
)";

std::set<std::string> listing(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.insert(entry.path().filename().string());
  return names;
}

class GplanOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_.write("box.obj", testing::kCubeObj);
    folder_.write("hand.obj", testing::kCubeObj);
    folder_.write("arm.urdf", kArmUrdf);
    scene_ = folder_.write("arm.yaml", kArmScene);
  }

  std::string path(const std::string& name) const {
    return (fs::path(folder_.path()) / name).string();
  }

  CommandResult plan(const std::string& arguments) const {
    return run_gplan("plan " + testing::shell_quoted(scene_) + " --backend cpu " + arguments);
  }

  // Expects exit 2 with one line naming `option` and `needle`, and every file of the
  // scratch folder as it was.
  void expect_refused(const std::string& arguments, const std::string& option,
                      const std::string& needle) const {
    std::vector<std::pair<std::string, std::string>> before;
    const std::size_t entries = listing(folder_.path()).size();
    for (const std::string& name : listing(folder_.path())) {
      if (fs::is_regular_file(fs::symlink_status(path(name))))
        before.emplace_back(name, testing::read_file(path(name)));
    }
    const CommandResult run = plan(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
    EXPECT_NE(run.output.find("gplan: " + option + " "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(needle), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("scene       "), std::string::npos) << "no planning: " << run.output;
    for (const auto& [name, text] : before) EXPECT_EQ(testing::read_file(path(name)), text) << name;
    EXPECT_EQ(listing(folder_.path()).size(), entries) << "nothing added";
  }

  ScratchFolder folder_;
  std::string scene_;
};

TEST_F(GplanOutputs, APathIsWrittenAndReportedByOption) {
  const std::string out = path("path.yaml");
  const CommandResult run = plan("--out " + testing::shell_quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("wrote       --out " + out), std::string::npos) << run.output;
  EXPECT_EQ(YAML::LoadFile(out)["entries"][0].as<std::string>(), "turn");
}

TEST_F(GplanOutputs, ADeviceIsRefusedAndStaysADevice) {
  struct stat before {};
  ASSERT_EQ(stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  expect_refused("--out /dev/null", "--out", "is a character device");
  struct stat after {};
  ASSERT_EQ(stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode)) << "/dev/null is still a device";
  EXPECT_EQ(after.st_ino, before.st_ino);
  EXPECT_EQ(after.st_rdev, before.st_rdev);
}

TEST_F(GplanOutputs, AFifoAndAFolderAreRefused) {
  ASSERT_EQ(mkfifo(path("pipe").c_str(), 0644), 0);
  expect_refused("--picture " + testing::shell_quoted(path("pipe")), "--picture", "is a FIFO");
  EXPECT_EQ(fs::status(path("pipe")).type(), fs::file_type::fifo);
  expect_refused("--save-roadmap " + testing::shell_quoted(folder_.path()), "--save-roadmap",
                 "is a folder");
}

TEST_F(GplanOutputs, AnEmptyNameIsRefused) {
  expect_refused("--out ''", "--out", "an empty file name");
}

TEST_F(GplanOutputs, TheSceneItsMeshesAndItsUrdfAreNeverOverwritten) {
  expect_refused("--out " + testing::shell_quoted(scene_), "--out",
                 "would overwrite the scene file");
  // The same files by other names: another spelling, a hard link.
  expect_refused("--picture " + testing::shell_quoted(folder_.path() + "/./box.obj"), "--picture",
                 "would overwrite a file the scene loads");
  expect_refused("--save-roadmap " + testing::shell_quoted(path("arm.urdf")), "--save-roadmap",
                 "would overwrite a file the scene loads");
  expect_refused("--out " + testing::shell_quoted(path("hand.obj")), "--out",
                 "would overwrite a file the scene loads");
  ASSERT_EQ(link(path("hand.obj").c_str(), path("hard.obj").c_str()), 0);
  expect_refused("--out " + testing::shell_quoted(path("hard.obj")), "--out",
                 "would overwrite a file the scene loads");
}

TEST_F(GplanOutputs, TheLoadedRoadmapIsNeverOverwritten) {
  const std::string roadmap = path("roadmap.bin");
  ASSERT_EQ(plan("--save-roadmap " + testing::shell_quoted(roadmap)).exit_code, 0);
  expect_refused("--load-roadmap " + testing::shell_quoted(roadmap) + " --save-roadmap " +
                     testing::shell_quoted(roadmap),
                 "--save-roadmap", "would overwrite the --load-roadmap file");
  expect_refused("--load-roadmap " + testing::shell_quoted(roadmap) + " --out " +
                     testing::shell_quoted(roadmap),
                 "--out", "would overwrite the --load-roadmap file");
}

TEST_F(GplanOutputs, TwoOutputsOnOnePathAreRefused) {
  expect_refused("--out " + testing::shell_quoted(path("same")) + " --picture " +
                     testing::shell_quoted(path("same")),
                 "--picture", "is also --out");
  folder_.write("existing", "kept\n");
  expect_refused("--out " + testing::shell_quoted(path("existing")) + " --save-roadmap " +
                     testing::shell_quoted(folder_.path() + "//existing"),
                 "--save-roadmap", "is also --out");
}

TEST_F(GplanOutputs, ASymbolicLinkIsWrittenThrough) {
  fs::create_directory(path("real"));
  const std::string target = folder_.write("real/path.yaml", "old\n");
  ASSERT_EQ(chmod(target.c_str(), 0640), 0);
  fs::create_symlink("real/path.yaml", path("link.yaml"));
  const CommandResult run = plan("--out " + testing::shell_quoted(path("link.yaml")));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::is_symlink(path("link.yaml"))) << "the link is kept";
  EXPECT_EQ(fs::read_symlink(path("link.yaml")), "real/path.yaml");
  EXPECT_EQ(YAML::LoadFile(target)["entries"][0].as<std::string>(), "turn") << "target written";
  struct stat status {};
  ASSERT_EQ(stat(target.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 07777, 0640u) << "permission bits kept";
  EXPECT_EQ(listing(path("real")).size(), 1u) << "no temporary file left";
}

TEST_F(GplanOutputs, ADanglingLinkIntoAMissingFolderIsRefused) {
  fs::create_symlink("missing/folder/path.yaml", path("dangling.yaml"));
  expect_refused("--out " + testing::shell_quoted(path("dangling.yaml")), "--out",
                 "does not exist (the symbolic link leads to");
  EXPECT_TRUE(fs::is_symlink(path("dangling.yaml")));
}

TEST_F(GplanOutputs, ALinkLoopAndAnOverlongNameAreClearErrors) {
  fs::create_symlink("loop2", path("loop1"));
  fs::create_symlink("loop1", path("loop2"));
  expect_refused("--out " + testing::shell_quoted(path("loop1")), "--out",
                 "too many symbolic links");
  expect_refused("--out " + testing::shell_quoted(path(std::string(300, 'x'))), "--out",
                 "the name is too long");
  const CommandResult run = plan("--out " + testing::shell_quoted(path(std::string(300, 'x'))));
  EXPECT_LT(run.output.size(), 600u) << "a long name is shortened in the message";
}

TEST_F(GplanOutputs, AReadOnlyFolderIsRefusedBeforePlanning) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  fs::create_directory(path("locked"));
  ASSERT_EQ(chmod(path("locked").c_str(), 0555), 0);
  expect_refused("--out " + testing::shell_quoted(path("locked/path.yaml")), "--out",
                 "cannot create files in folder");
  chmod(path("locked").c_str(), 0755);
}

TEST_F(GplanOutputs, NoPathSaysTheOutputsWereLeftAsTheyWere) {
  const std::string walled = folder_.write("walled.yaml", kWalledScene);
  const std::string out = folder_.write("path.yaml", "old\n");
  const CommandResult run = run_gplan(
      "plan " + testing::shell_quoted(walled) + " --backend cpu --time-limit 0.2 --out " +
      testing::shell_quoted(out) + " --picture " + testing::shell_quoted(path("path.svg")));
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_NE(run.output.find("gplan: no path, so nothing written to --out " + out + ", --picture " +
                            path("path.svg")),
            std::string::npos)
      << run.output;
  EXPECT_EQ(testing::read_file(out), "old\n");
  EXPECT_FALSE(fs::exists(path("path.svg")));
}

// Starts gplan with `arguments` (its output into `log`), returns its process id.
pid_t start_gplan(const std::vector<std::string>& arguments, const std::string& log) {
  std::vector<std::string> words{GPLAN_EXECUTABLE};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// Sends `signal_number` to a run after a second and expects it to end within another
// second with exit 128 + the signal, saying so, with nothing written and no temporary
// file left in `output_folder`.
void expect_clean_interruption(const std::vector<std::string>& arguments, int signal_number,
                               const std::string& output_folder, const std::string& log) {
  if (std::getenv("GPLANNER_GPLAN") != nullptr) GTEST_SKIP() << "gplan runs through a wrapper";
  const std::set<std::string> before = listing(output_folder);
  const pid_t pid = start_gplan(arguments, log);
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_EQ(kill(pid, signal_number), 0);
  const auto sent = std::chrono::steady_clock::now();
  int status = 0;
  pid_t ended = 0;
  while ((ended = waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() - sent < std::chrono::seconds(10)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  if (ended == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    FAIL() << "still running 10 s after the signal";
  }
  const std::string output = testing::read_file(log);
  EXPECT_LT(seconds, 1.0) << output;
  ASSERT_TRUE(WIFEXITED(status)) << "ended by the signal itself, not cleanly: " << output;
  EXPECT_EQ(WEXITSTATUS(status), 128 + signal_number) << output;
  const std::string name = signal_number == SIGINT   ? "SIGINT"
                           : signal_number == SIGHUP ? "SIGHUP"
                                                     : "SIGTERM";
  EXPECT_NE(output.find("gplan: interrupted by " + name + "; nothing written"), std::string::npos)
      << output;
  EXPECT_EQ(listing(output_folder), before) << "no output, no temporary file";
}

TEST_F(GplanOutputs, SigtermEndsALongPlanCleanly) {
  const std::string walled = folder_.write("walled.yaml", kWalledScene);
  ScratchFolder logs;
  fs::create_directory(path("outputs"));
  expect_clean_interruption(
      {"plan", walled, "--backend", "cpu", "--time-limit", "60", "--out", path("outputs/path.yaml"),
       "--picture", path("outputs/path.svg"), "--save-roadmap", path("outputs/roadmap.bin")},
      SIGTERM, path("outputs"), logs.path() + "/log");
}

TEST_F(GplanOutputs, SigintEndsALongPlanCleanly) {
  const std::string walled = folder_.write("walled.yaml", kWalledScene);
  ScratchFolder logs;
  fs::create_directory(path("outputs"));
  expect_clean_interruption({"plan", walled, "--backend", "cpu", "--time-limit", "60",
                             "--save-roadmap", path("outputs/roadmap.bin")},
                            SIGINT, path("outputs"), logs.path() + "/log");
}

TEST_F(GplanOutputs, SighupEndsALongPlanCleanly) {
  const std::string walled = folder_.write("walled.yaml", kWalledScene);
  ScratchFolder logs;
  fs::create_directory(path("outputs"));
  expect_clean_interruption(
      {"plan", walled, "--backend", "cpu", "--time-limit", "60", "--out", path("outputs/path.yaml"),
       "--save-roadmap", path("outputs/roadmap.bin")},
      SIGHUP, path("outputs"), logs.path() + "/log");
}

TEST_F(GplanOutputs, SigtermEndsALongCheckCleanly) {
  const std::string walled = folder_.write("walled.yaml", kWalledScene);
  ScratchFolder logs;
  fs::create_directory(path("outputs"));
  expect_clean_interruption(
      // Repeated so that it runs for seconds on any machine.
      {"check", walled, "--backend", "fcl", "--n", "200000", "--repeat", "1000", "--out",
       path("outputs/samples.txt")},
      SIGTERM, path("outputs"), logs.path() + "/log");
}

}  // namespace
}  // namespace gplanner

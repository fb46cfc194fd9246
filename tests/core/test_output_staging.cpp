// The output folder of a run: all outputs move into place or none, one run
// at a time (a lock), and staging folders of dead runs are removed.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pipeline_fixture.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {
const std::string kWrite = "pipeline: t\nstages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: " + touchcloud::test::gel_dome_cloud() +
                           "}\n  - id: w\n    plugin: cloud_writer\n    inputs: {cloud: read.cloud}\n"
                           "    params: {path: cloud.pcd}\n";

bool has_staging(const fs::path& out) {
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().filename().string().rfind(".touchcloud-staging-", 0) == 0) return true;
  return false;
}
}  // namespace

class OutputStaging : public touchcloud::test::PipelineFixture {
 protected:
  void run(const fs::path& out) {
    Pipeline p = load(kWrite);
    RunOptions o;
    o.out_dir = out;
    o.quiet = true;
    run_pipeline(p, o);
  }
};

// A folder where summary.json goes: the cloud must not be moved in without it.
TEST_F(OutputStaging, AFailedFinalMoveMovesNothing) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out / "summary.json");
  try {
    run(out);
    FAIL() << "the run succeeded";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("summary.json is a folder"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out / "cloud.pcd"));
  EXPECT_FALSE(has_staging(out));
}

// An earlier run's outputs stay as they were when a later run cannot move.
TEST_F(OutputStaging, ARolledBackMoveRestoresWhatItReplaced) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  test::write_file(out / "cloud.pcd", "earlier");
  fs::create_directories(out / "summary.json");
  EXPECT_THROW(run(out), RunError);
  EXPECT_EQ(test::read_file(out / "cloud.pcd"), "earlier");
  fs::remove(out / "summary.json");
  run(out);
  EXPECT_NE(test::read_file(out / "cloud.pcd"), "earlier");
  EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
}

TEST_F(OutputStaging, StagingFoldersOfDeadRunsAreRemoved) {
  const fs::path out = dir_ / "out";
  // A pid that surely ended: a child we started and reaped.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  const auto staging = [&](pid_t pid) { return out / (".touchcloud-staging-" + std::to_string(pid)); };
  const auto owner = [](pid_t pid) { return "touchcloud staging folder of process " + std::to_string(pid) + "\n"; };
  const fs::path stale = staging(child);
  fs::create_directories(stale);
  test::write_file(stale / ".touchcloud-owner", owner(child));
  test::write_file(stale / "partial.ply", "half");
  // One whose process lives (ours is not it: it is this test's parent).
  const fs::path alive = staging(::getppid());
  fs::create_directories(alive);
  test::write_file(alive / ".touchcloud-owner", owner(::getppid()));
  run(out);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(alive));
  EXPECT_TRUE(fs::exists(out / "cloud.pcd"));
}

// A folder of a staging folder's name that no run made (a user's own, or
// one whose owner file names another process) is never removed.
TEST_F(OutputStaging, OnlyStagingFoldersARunMadeAreRemoved) {
  const fs::path out = dir_ / "out";
  // Two pids that surely ended.
  pid_t dead[2];
  for (pid_t& child : dead) {
    child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
  }
  const fs::path mine = out / (".touchcloud-staging-" + std::to_string(dead[0]));
  fs::create_directories(mine);
  test::write_file(mine / "kept.ply", "a user's file");
  const fs::path other = out / (".touchcloud-staging-" + std::to_string(dead[1]));
  fs::create_directories(other);
  test::write_file(other / ".touchcloud-owner", "touchcloud staging folder of process " + std::to_string(dead[0]) + "\n");
  run(out);
  EXPECT_EQ(test::read_file(mine / "kept.ply"), "a user's file");
  EXPECT_TRUE(fs::exists(other / ".touchcloud-owner"));
  EXPECT_TRUE(fs::exists(out / "cloud.pcd"));
}

TEST_F(OutputStaging, ASecondRunIntoAFolderInUseIsRefused) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  const int fd = ::open(out.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);  // as a run in progress holds it
  try {
    run(out);
    FAIL() << "ran into a locked folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is in use by another touchcloud run"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out / "cloud.pcd"));
  ::close(fd);
  run(out);
  EXPECT_TRUE(fs::exists(out / "cloud.pcd"));
}

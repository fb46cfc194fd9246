// What a run promises on failure, through the real binary: exit statuses and
// messages for bad seeds and files, a full disk (exit 1, nothing in place),
// Ctrl-C and SIGTERM (staging removed), two runs into one folder (a lock),
// and a score batch that goes on past a corrupt mesh.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "test_support.hpp"

using touchcloud::test::run_cli;
using touchcloud::test::TempDir;
using touchcloud::test::write_file;
namespace fs = std::filesystem;

namespace {

const std::string kCloud = touchcloud::test::gel_dome_cloud();
const std::string kDemo = (touchcloud::test::source_dir() / "pipelines/downsample_cloud.yaml").string();
const std::string kTestPlugins = "TOUCHCLOUD_PLUGIN_PATH=" TOUCHCLOUD_TEST_PLUGIN_DIR;

// Reads, writes the cloud (a partial output in staging), then waits ~30 s.
std::string slow_pipeline() {
  return "pipeline: slow\nstages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: " + kCloud +
         "}\n  - id: write\n    plugin: cloud_writer\n    params: {path: cloud.pcd}\n    inputs: {cloud: read.cloud}\n"
         "  - id: wait\n    plugin: test_rendezvous\n    params: {role: wait, timeout_ms: 30000}\n";
}

std::vector<fs::path> staging_folders(const fs::path& out) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(".touchcloud-staging-", 0) == 0) found.push_back(it->path());
  return found;
}

// Starts `touchcloud run PIPELINE --out OUT --quiet` and returns once its
// staging folder holds the written cloud.
pid_t start_slow_run(const fs::path& pipeline, const fs::path& out) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGINT, SIG_DFL);  // a background test runner may ignore it
    ::setenv("TOUCHCLOUD_PLUGIN_PATH", TOUCHCLOUD_TEST_PLUGIN_DIR, 1);
    ::execl(touchcloud::test::cli_path().c_str(), "touchcloud", "run", pipeline.c_str(), "--out", out.c_str(),
            "--quiet", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int i = 0; i < 400; ++i) {
    for (const auto& s : staging_folders(out))
      if (fs::exists(s / "cloud.pcd")) return pid;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ADD_FAILURE() << "the run never wrote its cloud into staging";
  return pid;
}

}  // namespace

TEST(CliFailures, ASeedOutsideZeroToTwoToTheSixtyFourIsBadInput) {
  for (const std::string seed : {"-1", "18446744073709551616", "99999999999999999999", "1e3"}) {
    const auto r = run_cli({"validate", kDemo});  // the pipeline itself is fine
    ASSERT_EQ(r.exit_code, 0) << r.err;
    TempDir dir;
    const auto run = run_cli({"run", kDemo, "--seed", seed, "--out", (dir / "out").string()});
    EXPECT_EQ(run.exit_code, 2) << seed << ": " << run.err;
    EXPECT_NE(run.err.find("is not a seed"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
}

// A file size limit (RLIMIT_FSIZE, with SIGXFSZ ignored) fails writes as a
// full disk does.
TEST(CliFailures, AFullDiskIsExitOneNamingTheFileWithNothingInPlace) {
  TempDir dir;
  const std::string cmd = "ulimit -f 4; trap '' XFSZ; exec '" + touchcloud::test::cli_path().string() + "' run '" +
                          kDemo + "' --quiet --out '" + (dir / "out").string() + "' 2>'" + (dir / "err").string() + "'";
  const int status = std::system(("bash -c \"" + cmd + "\"").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = touchcloud::test::read_file(dir / "err");
  EXPECT_NE(err.find("gel_dome_thinned.ply"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out/gel_dome_thinned.ply"));
  EXPECT_FALSE(fs::exists(dir / "out/summary.json"));
  EXPECT_TRUE(staging_folders(dir / "out").empty());
}

// Without the caller ignoring SIGXFSZ, the signal would end the run
// without a word and leave its partial file in staging.
TEST(CliFailures, AFileSizeLimitIsExitOneNamingTheFileWithNothingInPlace) {
  TempDir dir;
  const std::string cmd = "ulimit -f 4; exec '" + touchcloud::test::cli_path().string() + "' run '" + kDemo +
                          "' --quiet --out '" + (dir / "out").string() + "' 2>'" + (dir / "err").string() + "'";
  const int status = std::system(("bash -c \"" + cmd + "\"").c_str());
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = touchcloud::test::read_file(dir / "err");
  EXPECT_NE(err.find("touchcloud: error: "), std::string::npos) << err;
  EXPECT_NE(err.find("gel_dome_thinned.ply"), std::string::npos) << err;
  EXPECT_NE(err.find("it reached the file-size limit, ulimit -f: 4096 bytes"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out/gel_dome_thinned.ply"));
  EXPECT_FALSE(fs::exists(dir / "out/summary.json"));
  EXPECT_TRUE(staging_folders(dir / "out").empty());
}

TEST(CliFailures, SigtermAndCtrlCRemoveTheStagingFolder) {
  for (int sig : {SIGTERM, SIGINT}) {
    TempDir dir;
    write_file(dir / "slow.yaml", slow_pipeline());
    const pid_t pid = start_slow_run(dir / "slow.yaml", dir / "out");
    ASSERT_EQ(::kill(pid, sig), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << strsignal(sig) << " status " << status;
    EXPECT_TRUE(staging_folders(dir / "out").empty()) << strsignal(sig);
    EXPECT_FALSE(fs::exists(dir / "out/cloud.pcd"));
  }
}

TEST(CliFailures, ASecondRunIntoTheSameOutIsRefusedWhileTheFirstRuns) {
  TempDir dir;
  write_file(dir / "slow.yaml", slow_pipeline());
  const pid_t first = start_slow_run(dir / "slow.yaml", dir / "out");
  const auto second = run_cli({"run", kDemo, "--out", (dir / "out").string(), "--quiet"});
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_NE(second.err.find("is in use by another touchcloud run"), std::string::npos) << second.err;
  ::kill(first, SIGTERM);
  ::waitpid(first, nullptr, 0);
  EXPECT_FALSE(fs::exists(dir / "out/gel_dome_thinned.ply"));
  EXPECT_EQ(run_cli({"run", kDemo, "--out", (dir / "out").string(), "--quiet"}).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir / "out/gel_dome_thinned.ply"));
}

TEST(CliFailures, AFolderAsThePipelineIsBadInput) {
  TempDir dir;
  const auto r = run_cli({"validate", dir.path().string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("touchcloud: error: " + dir.path().string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is a folder, not a file"), std::string::npos) << r.err;
}

// The batch goes on past a binary mesh declaring more faces than it holds
// (the former VTK reader aborted on it with a double free) and prints the
// good rows.
TEST(CliFailures, AScoreBatchGoesOnPastACorruptMesh) {
  TempDir dir;
  std::string bad = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                    "property double z\nelement face 9\nproperty list uchar int vertex_indices\nend_header\n";
  const double xyz[12] = {0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 3, 0};
  bad.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  const unsigned char quad[17] = {4, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0};
  bad.append(reinterpret_cast<const char*>(quad), sizeof quad);
  write_file(dir / "bad.ply", bad);
  write_file(dir / "list.csv", "estimate,ground_truth\n" + kCloud + ",bad.ply\n" + kCloud + "," + kCloud + "\n");
  const auto r = run_cli({"score", (dir / "list.csv").string(), "--json"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find((dir / "bad.ply").string()), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("chamfer_est_to_gt_mm"), std::string::npos) << "the good row:\n" << r.out;
}

// touchcloud stream through the real binary: a recording streamed to its
// end gives the clouds `run` gives, summary.json counts the frames and
// gives each stage's latency percentiles; --frames N stops after N; Ctrl-C
// ends the stream with its outputs written (status 0); a pipeline without a
// top-level loop and a video cut short are refused (status 2, nothing
// written).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "press_videos.hpp"
#include "test_support.hpp"

using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

const std::string kCalibration =
    (source_dir() / "sample_clouds/gelsight_ball/photometric_calibration.yaml").string();

std::string gelsight_pipeline(const std::string& source) {
  return "pipeline: gelsight_stream\nstages:\n  - id: frames\n    loop:\n      max_iterations: 100\n"
         "      until: cam.done\n      stages:\n"
         "        - id: cam\n          plugin: camera_source\n          params: {" + source + "}\n"
         "        - id: depth\n          plugin: photometric_depth\n"
         "          params: {calibration: " + kCalibration + ", border: free}\n"
         "          inputs: {image: cam.frame, reference: cam.reference}\n"
         "        - id: cloud\n          plugin: height_to_cloud\n          params: {points: all, stride_px: 4}\n"
         "          inputs: {height: depth.height}\n"
         "        - id: write\n          plugin: cloud_writer\n          params: {path: 'cloud_{iteration}.pcd'}\n"
         "          inputs: {cloud: cloud.cloud}\n";
}

nlohmann::json summary(const fs::path& out) { return nlohmann::json::parse(read_file(out / "summary.json")); }

class StreamVerb : public ::testing::Test {
 protected:
  void SetUp() override {
    frames_ = press_frames();
    ASSERT_TRUE(write_video(dir_ / "presses.mkv", "FFV1", frames_));
    write_file(dir_ / "gelsight.yaml", gelsight_pipeline("video: presses.mkv"));
  }
  TempDir dir_;
  std::vector<cv::Mat> frames_;
};

TEST_F(StreamVerb, ARecordingStreamedToItsEndGivesTheCloudsOfRun) {
  const CliResult streamed = run_cli({"stream", (dir_ / "gelsight.yaml").string(), "--out", (dir_ / "s").string(), "-q"});
  ASSERT_EQ(streamed.exit_code, 0) << streamed.err;
  EXPECT_NE(streamed.out.find("streamed 5 frames"), std::string::npos) << streamed.out;
  EXPECT_NE(streamed.out.find("(end of source)"), std::string::npos) << streamed.out;
  const CliResult ran = run_cli({"run", (dir_ / "gelsight.yaml").string(), "--out", (dir_ / "r").string(), "-q"});
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  for (int k = 0; k < 5; ++k) {
    const std::string cloud = "cloud_" + std::to_string(k) + ".pcd";
    EXPECT_EQ(read_file(dir_ / "s" / cloud), read_file(dir_ / "r" / cloud)) << cloud;
  }
  const nlohmann::json j = summary(dir_ / "s");
  EXPECT_EQ(j["loops"]["frames"]["iterations"], 5);
  EXPECT_EQ(j["metrics"]["cam.frames_captured"]["value"], 5.0);
  EXPECT_EQ(j["metrics"]["cam.frames_processed"]["value"], 5.0);
  EXPECT_EQ(j["metrics"]["cam.frames_dropped"]["value"], 0.0);
  EXPECT_GT(j["metrics"]["cam.rate_fps"]["value"].get<double>(), 0.0);
  const double p50 = j["metrics"]["cam.latency_p50_ms"]["value"], p99 = j["metrics"]["cam.latency_p99_ms"]["value"];
  EXPECT_GT(p50, 0.0);
  EXPECT_GE(p99, p50);
  for (const auto& stage : j["stages"]) {
    ASSERT_TRUE(stage.contains("latency_ms")) << stage["id"];
    EXPECT_LE(stage["latency_ms"]["p50"].get<double>(), stage["latency_ms"]["p95"].get<double>());
    EXPECT_LE(stage["latency_ms"]["p95"].get<double>(), stage["latency_ms"]["p99"].get<double>());
  }
  // run keeps its summary as it was: no per-call latencies.
  EXPECT_FALSE(summary(dir_ / "r")["stages"][0].contains("latency_ms"));
}

TEST_F(StreamVerb, FramesStopsAfterThatManyAndTheProgressLineShowsDrops) {
  const CliResult r = run_cli({"stream", (dir_ / "gelsight.yaml").string(), "--frames", "2", "--out",
                               (dir_ / "s").string(), "-q", "--progress"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("streamed 2 frames"), std::string::npos) << r.out;
  EXPECT_EQ(summary(dir_ / "s")["metrics"]["cam.frames_processed"]["value"], 2.0);
  EXPECT_NE(r.err.find("2 frames"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0 dropped"), std::string::npos) << r.err;
  EXPECT_EQ(run_cli({"stream", (dir_ / "gelsight.yaml").string(), "--frames", "0"}).exit_code, 2);
}

// Ctrl-C ends the stream after the frame in hand: the clouds so far and
// summary.json are written, the status is 0.
TEST_F(StreamVerb, CtrlCEndsTheStreamWithItsOutputsWritten) {
  std::vector<cv::Mat> many;
  for (int k = 0; k < 200; ++k) many.push_back(frames_[static_cast<std::size_t>(k % 6)]);
  write_frame_files(dir_.path() / "long", many);
  write_file(dir_ / "long.yaml", gelsight_pipeline("frames: 'long/frame_{iteration}.png', fps: 20, realtime: true"));
  const fs::path out = dir_ / "out";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGINT, SIG_DFL);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::execl(cli_path().c_str(), "touchcloud", "stream", (dir_ / "long.yaml").c_str(), "--out", out.c_str(), "-q",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Once frames flow (a cloud in the staging folder), interrupt.
  bool flowing = false;
  for (int i = 0; i < 400 && !flowing; ++i) {
    std::error_code ec;
    for (fs::directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec))
      if (fs::exists(it->path() / "cloud_3.pcd")) flowing = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  EXPECT_TRUE(flowing);
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const nlohmann::json j = summary(out);
  const double processed = j["metrics"]["cam.frames_processed"]["value"];
  EXPECT_GE(processed, 4.0);
  EXPECT_LT(processed, 100.0);
  for (int k = 0; k < static_cast<int>(processed); ++k) EXPECT_TRUE(fs::exists(out / ("cloud_" + std::to_string(k) + ".pcd")));
}

TEST_F(StreamVerb, APipelineWithoutALoopOrAVideoCutShortIsRefused) {
  write_file(dir_ / "flat.yaml", "pipeline: flat\nstages:\n  - id: cam\n    plugin: camera_source\n"
                                 "    params: {video: presses.mkv}\n");
  const CliResult flat = run_cli({"stream", (dir_ / "flat.yaml").string(), "--out", (dir_ / "f").string()});
  EXPECT_EQ(flat.exit_code, 2);
  EXPECT_NE(flat.err.find("flat.yaml has none (put its source and per-frame stages in a loop"), std::string::npos) << flat.err;

  std::vector<cv::Mat> frames;
  for (int copy = 0; copy < 4; ++copy) frames.insert(frames.end(), frames_.begin(), frames_.end());
  ASSERT_TRUE(write_video(dir_ / "whole.avi", "MJPG", frames));
  const std::string bytes = read_file(dir_ / "whole.avi");
  write_file(dir_ / "cut.avi", bytes.substr(0, bytes.size() / 2));
  write_file(dir_ / "cut.yaml", gelsight_pipeline("video: cut.avi"));
  const CliResult cut = run_cli({"stream", (dir_ / "cut.yaml").string(), "--out", (dir_ / "c").string(), "-q"});
  EXPECT_EQ(cut.exit_code, 2);
  // The cut falls inside a frame, which FFmpeg finds damaged.
  EXPECT_NE(cut.err.find("cut.avi is damaged at or before its frame "), std::string::npos) << cut.err;
  EXPECT_NE(cut.err.find("(corrupt or cut short): FFmpeg says '"), std::string::npos) << cut.err;
  EXPECT_FALSE(fs::exists(dir_ / "c" / "summary.json"));
}

// A camera that disappears mid-stream (a video cut short stands in): the
// error names it, and what was recorded up to then is complete: every row of
// its index has its frame, and it replays.
TEST_F(StreamVerb, ARecordingSurvivesTheSourceEndingMidStream) {
  std::vector<cv::Mat> frames;
  for (int copy = 0; copy < 4; ++copy) frames.insert(frames.end(), frames_.begin(), frames_.end());
  ASSERT_TRUE(write_video(dir_ / "whole.avi", "MJPG", frames));
  const std::string bytes = read_file(dir_ / "whole.avi");
  write_file(dir_ / "cut.avi", bytes.substr(0, bytes.size() / 2));
  const fs::path rec = dir_ / "rec";
  write_file(dir_ / "cut.yaml", gelsight_pipeline("video: cut.avi, record: " + rec.string()));
  const CliResult cut = run_cli({"stream", (dir_ / "cut.yaml").string(), "--out", (dir_ / "c").string(), "-q"});
  EXPECT_EQ(cut.exit_code, 2);
  // The cut falls inside a frame, which FFmpeg finds damaged.
  EXPECT_NE(cut.err.find("cut.avi is damaged at or before its frame "), std::string::npos) << cut.err;
  EXPECT_NE(cut.err.find("(corrupt or cut short): FFmpeg says '"), std::string::npos) << cut.err;
  const std::string index = read_file(rec / "index.csv");
  const long rows = std::count(index.begin(), index.end(), '\n') - 1;
  EXPECT_GE(rows, 3);
  EXPECT_LT(rows, static_cast<long>(frames.size()));
  for (long k = 0; k < rows; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frames/%06ld.png", k);
    EXPECT_NE(index.find(name), std::string::npos) << name;
    EXPECT_FALSE(cv::imread((rec / name).string()).empty()) << name;
  }
  write_file(dir_ / "replay.yaml", gelsight_pipeline("frames: rec/index.csv"));
  const CliResult replay = run_cli({"run", (dir_ / "replay.yaml").string(), "--out", (dir_ / "r").string(), "-q"});
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  EXPECT_EQ(summary(dir_ / "r")["metrics"]["cloud.points"]["series"].size(), static_cast<std::size_t>(rows - 1));
}

}  // namespace

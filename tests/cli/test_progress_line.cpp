// Progress on long batches: the line's text, and sweep / score printing it
// in a log only when asked (--progress), quiet otherwise.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <regex>
#include <thread>

#include "counting_pipeline.hpp"
#include "progress_line.hpp"
#include "test_support.hpp"

using touchcloud::cli::progress_text;
using touchcloud::test::run_cli;
using touchcloud::test::write_file;

namespace {
const std::string kTestPlugins = "TOUCHCLOUD_PLUGIN_PATH=" TOUCHCLOUD_TEST_PLUGIN_DIR;
}  // namespace

TEST(ProgressLine, SaysDoneTotalRateAndTimeLeft) {
  EXPECT_EQ(progress_text(0, 10, 3.0, "runs"), "0/10 runs");
  EXPECT_EQ(progress_text(3, 10, 6.0, "runs"), "3/10 runs, 0.5 runs/s, about 14 s left");
  EXPECT_EQ(progress_text(40, 1000, 10.0, "estimates"), "40/1000 estimates, 4 estimates/s, about 4 min left");
  EXPECT_EQ(progress_text(1, 1000, 30.0, "runs"), "1/1000 runs, 0.0333 runs/s, about 8.3 h left");
  EXPECT_EQ(progress_text(10, 10, 2.0, "runs"), "10/10 runs, 5 runs/s");
  // A count that began part way (a resumed training run): the rate is of what was done since.
  EXPECT_EQ(progress_text(7, 10, 4.0, "epochs", 5), "7/10 epochs, 0.5 epochs/s, about 6 s left");
  EXPECT_EQ(progress_text(5, 10, 4.0, "epochs", 5), "5/10 epochs");
  // No total known (a camera's frames): the count and rate, no time left.
  EXPECT_EQ(progress_text(120, 0, 2.0, "frames"), "120 frames, 60 frames/s");
}

// A long stage's count follows the loop's, with its own rate; a new
// iteration of the loop drops it; nothing counted prints nothing.
TEST(ProgressLine, AStagesStepFollowsTheLoopsCount) {
  using touchcloud::cli::ProgressLine;
  const auto final_line = [](const std::function<void(ProgressLine&)>& feed) {
    testing::internal::CaptureStderr();
    {
      ProgressLine line(0, "", true);
      feed(line);
      line.finish();
    }
    return testing::internal::GetCapturedStderr();
  };
  EXPECT_EQ(final_line([](ProgressLine&) {}), "");
  EXPECT_EQ(final_line([](ProgressLine& l) { l.set_step("train", 0, 4, "epochs"); }), "progress: train: 0/4 epochs\n");
  const std::string both = final_line([](ProgressLine& l) {
    l.set(1, 3, "l iterations");
    l.set_step("train", 0, 4, "epochs");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    l.set_step("train", 2, 4, "epochs");
  });
  EXPECT_TRUE(std::regex_match(both, std::regex("progress: 1/3 l iterations, [0-9.e+]+ l iterations/s, about .* left; "
                                                "train: 2/4 epochs, [0-9.e+]+ epochs/s, about .* left\n")))
      << both;
  EXPECT_EQ(final_line([](ProgressLine& l) {
              l.set(1, 3, "l iterations");
              l.set_step("train", 2, 4, "epochs");
              l.set(2, 3, "l iterations");
            }).find("train"),
            std::string::npos);
}

TEST(ProgressLine, SweepShowsItInALogOnlyWhenAsked) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", touchcloud::test::counting_pipeline());
  const std::vector<std::string> sweep = {"sweep", (dir / "p.yaml").string(), "--vary", "c.step=0.5,2",
                                          "--repeats", "2", "--accuracy", "c.value", "--out"};
  auto args = sweep;
  args.push_back((dir / "quiet").string());
  const auto quiet = run_cli(args, kTestPlugins);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("progress:"), std::string::npos) << quiet.err;
  EXPECT_NE(quiet.err.find("[4/4] c.step=2 seed 1: "), std::string::npos) << quiet.err;  // the run log stays
  args = sweep;
  args.insert(args.end(), {(dir / "shown").string(), "--progress"});
  const auto shown = run_cli(args, kTestPlugins);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_NE(shown.err.find("progress: 4/4 runs, "), std::string::npos) << shown.err;
}

TEST(ProgressLine, ScoreShowsItInALogOnlyWhenAsked) {
  touchcloud::test::TempDir dir;
  const std::string cloud = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                            "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n0 0 0\n1 0 0\n";
  write_file(dir / "gt.pcd", cloud);
  write_file(dir / "a.pcd", cloud);
  write_file(dir / "b.pcd", cloud);
  const std::vector<std::string> score = {"score", "--gt", (dir / "gt.pcd").string(), (dir / "a.pcd").string(),
                                          (dir / "b.pcd").string(), "--json"};
  const auto quiet = run_cli(score);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  auto args = score;
  args.push_back("--progress");
  const auto shown = run_cli(args);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_NE(shown.err.find("progress: 2/2 estimates, "), std::string::npos) << shown.err;
}

TEST(ProgressLine, RunShowsItsLoopInALogOnlyWhenAsked) {
  touchcloud::test::TempDir dir;
  write_file(dir / "p.yaml", touchcloud::test::counting_pipeline());
  const auto quiet = run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / "a").string()}, kTestPlugins);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("progress:"), std::string::npos) << quiet.err;
  const auto shown =
      run_cli({"run", (dir / "p.yaml").string(), "--out", (dir / "b").string(), "--progress"}, kTestPlugins);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_NE(shown.err.find("progress: 3/3 l iterations, "), std::string::npos) << shown.err;
}

// A recording through the capture thread: each frame knows whether another
// follows (read ahead, so a stage's `done` waits for nothing), and paced as
// a camera each frame is stamped with the time it was due, not when the
// capture thread woke; a device frame's capture time is its buffer time
// where that is on the steady clock.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "test_support.hpp"
#include "touchcloud/plugin_kit/camera/frame_feed.hpp"

using namespace touchcloud::camera;
using touchcloud::test::TempDir;
using std::chrono::steady_clock;

namespace {

// Five 8 x 6 frames as '{iteration}' files, paced at `fps`.
std::unique_ptr<FrameFeed> five_frames(const TempDir& dir, double fps, bool realtime) {
  for (int k = 0; k < 5; ++k)
    cv::imwrite((dir / ("frame_" + std::to_string(k) + ".png")).string(), cv::Mat(6, 8, CV_8UC3, cv::Scalar(k, k, k)));
  CaptureSettings s;
  s.kind = SourceKind::image_files;
  s.source = (dir / "frame_{iteration}.png").string();
  s.fps = fps;
  return std::make_unique<FrameFeed>(std::make_unique<Capture>(s), 8, WhenBehind::block, realtime);
}

std::vector<Shot> all(FrameFeed& feed) {
  std::vector<Shot> shots;
  while (std::optional<Shot> shot = feed.next(5.0)) shots.push_back(std::move(*shot));
  return shots;
}

}  // namespace

TEST(FrameFeed, ARecordingsFramesSayWhetherAnotherFollows) {
  TempDir dir;
  const std::vector<Shot> shots = all(*five_frames(dir, 100, false));
  ASSERT_EQ(shots.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(shots[k].last, k == 4) << k;
    if (k < 4) {
      ASSERT_TRUE(shots[k].next_clock_s) << k;
      EXPECT_DOUBLE_EQ(*shots[k].next_clock_s, shots[k + 1].clock_s) << k;
    } else {
      EXPECT_FALSE(shots[k].next_clock_s);
    }
  }
}

TEST(FrameFeed, PacedAsACameraEachFrameIsStampedWhenItWasDue) {
  TempDir dir;
  const std::vector<Shot> shots = all(*five_frames(dir, 50, true));
  ASSERT_EQ(shots.size(), 5u);
  for (std::size_t k = 1; k < 5; ++k) {
    const double apart_s = std::chrono::duration<double>(shots[k].captured_at - shots[0].captured_at).count();
    EXPECT_NEAR(apart_s, shots[k].stamp.timestamp_s, 1e-6) << k;  // 20 ms a frame, to the microsecond
  }
}

TEST(FrameFeed, ADeviceFrameIsStampedWithItsBufferTimeWhereThatIsOnTheSteadyClock) {
  const steady_clock::time_point now = steady_clock::now();
  const double now_ms = std::chrono::duration<double, std::milli>(now.time_since_epoch()).count();
  const auto ms_before = [&](steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(now - t).count();
  };
  EXPECT_NEAR(ms_before(device_capture_time(now, now_ms - 12.5)), 12.5, 1e-3);
  EXPECT_EQ(device_capture_time(now, now_ms + 5.0), now);     // in the future: another clock
  EXPECT_EQ(device_capture_time(now, now_ms - 5000.0), now);  // five seconds old: another clock
  EXPECT_EQ(device_capture_time(now, 1.7e12), now);           // wall-clock milliseconds
}

// FFmpeg's log caught by the camera sources: error-level messages kept
// (the first 8), quieter ones dropped, nothing printed.
#include <gtest/gtest.h>

extern "C" {
#include <libavutil/log.h>
}

#include "ffmpeg_messages.hpp"

using namespace touchcloud::camera;

TEST(FfmpegMessages, ErrorsAreCaughtInOrderAndNothingIsPrinted) {
  catch_ffmpeg_messages();
  caught_ffmpeg_messages();
  testing::internal::CaptureStderr();
  av_log(nullptr, AV_LOG_ERROR, "moov atom not found\n");
  av_log(nullptr, AV_LOG_WARNING, "a warning OpenCV's level hides anyway\n");
  for (int i = 0; i < 10; ++i) av_log(nullptr, AV_LOG_FATAL, "damage %d\n", i);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  const std::vector<std::string> caught = caught_ffmpeg_messages();
  ASSERT_EQ(caught.size(), 8u);
  EXPECT_EQ(caught[0], "moov atom not found");
  EXPECT_EQ(caught[7], "damage 6");
  EXPECT_TRUE(caught_ffmpeg_messages().empty());
  EXPECT_EQ(ffmpeg_says({"a", "b"}), "FFmpeg says 'a'; 'b'");
}

// FFmpeg's log caught by the camera sources: error-level messages kept
// (the first 8), quieter ones dropped, nothing printed; a message caught
// while several video files are read names them all.
#include <gtest/gtest.h>

extern "C" {
#include <libavutil/log.h>
}

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "ffmpeg_messages.hpp"
#include "test_support.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/plugin_kit/camera/capture.hpp"

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

TEST(FfmpegMessages, AMessageNamesTheOtherVideoFilesReadAtTheSameTime) {
  auto left = reading_video("left.mp4");
  EXPECT_TRUE(videos_read_besides(left).empty());
  {
    auto right = reading_video("right.mp4");
    auto third = reading_video("third.mp4");
    EXPECT_EQ(videos_read_besides(left), (std::vector<std::string>{"right.mp4", "third.mp4"}));
    EXPECT_EQ(videos_read_besides(right), (std::vector<std::string>{"left.mp4", "third.mp4"}));
    EXPECT_EQ(ffmpeg_says({"a"}, third),
              "FFmpeg says 'a' (FFmpeg's log is one for the process, and it was reading left.mp4 and right.mp4 at "
              "the same time: the damage may be in one of those instead)");
  }
  EXPECT_TRUE(videos_read_besides(left).empty());
}

namespace {

// 30 frames of a moving disc on noise, as MPEG-4 (whose decoder logs from
// its own frame threads); `damaged`: a stretch of its frames' bytes flipped.
std::string press_video(const touchcloud::test::TempDir& dir, const std::string& name, bool damaged) {
  const std::string path = (dir / name).string();
  {
    cv::VideoWriter writer(path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 30, cv::Size(160, 120));
    cv::RNG rng(7);
    for (int k = 0; k < 30; ++k) {
      cv::Mat frame(120, 160, CV_8UC3);
      rng.fill(frame, cv::RNG::UNIFORM, 0, 255);
      cv::circle(frame, {40 + 2 * k, 60}, 20, cv::Scalar(200, 90, 30), -1);
      writer.write(frame);
    }
  }
  if (damaged) {
    std::string bytes = touchcloud::test::read_file(path);
    const std::size_t from = bytes.find("mdat"), to = bytes.find("moov");
    for (std::size_t at = from + (to - from) / 3; at < from + (to - from) / 2; at += 13)
      bytes[at] = static_cast<char>(bytes[at] ^ 0x5A);
    touchcloud::test::write_file(path, bytes);
  }
  return path;
}

// Reads both files frame by frame, as a stereo pair does; the first error.
std::string read_together(const std::vector<std::string>& files) {
  std::vector<std::unique_ptr<Capture>> captures;
  for (const std::string& f : files) {
    CaptureSettings s;
    s.kind = SourceKind::video_file;
    s.source = f;
    captures.push_back(std::make_unique<Capture>(s));
  }
  try {
    for (bool more = true; more;) {
      more = false;
      for (auto& c : captures) more = c->next().has_value() || more;
    }
  } catch (const touchcloud::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// FFmpeg's log is one for the process and its frame threads' messages carry
// no file: read alone, the damage is the file's; read beside another video,
// the error names both rather than blame one it cannot know.
TEST(FfmpegMessages, ADamagedVideoReadBesideAnotherNamesBoth) {
  touchcloud::test::TempDir dir;
  const std::string damaged = press_video(dir, "damaged.mp4", true), whole = press_video(dir, "whole.mp4", false);
  testing::internal::CaptureStderr();
  const std::string alone = read_together({damaged});
  const std::string beside = read_together({whole, damaged});
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_NE(alone.find("damaged.mp4 is damaged at or before its frame"), std::string::npos) << alone;
  EXPECT_EQ(alone.find("at the same time"), std::string::npos) << alone;
  EXPECT_NE(beside.find("FFmpeg says '[mpeg4 @ "), std::string::npos) << beside;
  // The error is raised by whichever read caught the message; it names the other file as well.
  EXPECT_NE(beside.find("whole.mp4"), std::string::npos) << beside;
  EXPECT_NE(beside.find("damaged.mp4"), std::string::npos) << beside;
  EXPECT_NE(beside.find(" at the same time: the damage may be in that file instead)"), std::string::npos) << beside;
  // Once a file has ended it is no longer being read.
  EXPECT_EQ(read_together({whole}), "");
}

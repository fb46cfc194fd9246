// camera_source refuses what it cannot deliver, at validation where it can
// and always naming the source: a camera that does not exist or is not a
// camera, a file that is not a video, a damaged video (FFmpeg's words in
// the error, not on the terminal), a video cut short, frames of another
// size, a crop that does not fit, and a source that stops delivering (a
// bounded wait, never a hang).
#include <fstream>

#include "pipeline_fixture.hpp"
#include "press_videos.hpp"

using namespace touchcloud;
using namespace touchcloud::test;
namespace fs = std::filesystem;

namespace {

class CameraErrors : public PipelineFixture {
 protected:
  static std::string source_stage(const std::string& params) {
    return "stages:\n  - id: frames\n    loop:\n      max_iterations: 100\n      until: cam.done\n"
           "      stages:\n        - id: cam\n          plugin: camera_source\n          params: {" + params + "}\n";
  }
  // The one diagnostic loading the source stage gives.
  std::string load_error(const std::string& params) {
    const auto d = errors(source_stage(params));
    if (d.size() != 1) return "expected one diagnostic, got " + std::to_string(d.size());
    return d[0].message;
  }
  // The press frames with their first six three times more: a recording
  // long enough to damage in its middle.
  static std::vector<cv::Mat> longer_presses() {
    std::vector<cv::Mat> frames = press_frames();
    for (int copy = 0; copy < 3; ++copy) frames.insert(frames.end(), frames.begin(), frames.begin() + 6);
    return frames;
  }
  // What running it throws.
  template <class Error>
  std::string run_error(const std::string& params) {
    Pipeline p = load(source_stage(params));
    RunOptions o;
    o.quiet = true;
    try {
      run_pipeline(p, o);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  }
};

TEST_F(CameraErrors, ACameraThatDoesNotExistIsRefusedAtValidation) {
  const std::string e = load_error("device: /dev/video97");
  EXPECT_NE(e.find("parameter 'device': the camera /dev/video97 does not exist"), std::string::npos) << e;
  const std::string by_number = load_error("device: '97'");
  EXPECT_NE(by_number.find("the camera /dev/video97 does not exist"), std::string::npos) << by_number;
}

TEST_F(CameraErrors, ADeviceThatIsNotACameraIsRefusedWhenOpened) {
  const std::string e = run_error<InputError>("device: /dev/null, frame_timeout_s: 1");
  EXPECT_NE(e.find("the camera /dev/null cannot be opened"), std::string::npos) << e;
}

TEST_F(CameraErrors, AFileThatIsNotAVideoIsRefusedAtValidation) {
  std::ofstream(dir_ / "noise.mkv") << std::string(5000, 'x');
  const std::string e = load_error("video: noise.mkv");
  EXPECT_NE(e.find("parameter 'video'"), std::string::npos) << e;
  EXPECT_NE(e.find("noise.mkv cannot be opened"), std::string::npos) << e;
}

// A video whose header or frames are damaged: an error quoting FFmpeg,
// naming the file (and the frame), and nothing of FFmpeg's on the terminal,
// where OpenCV's backend lets FFmpeg print ("moov atom not found",
// "ac-tex damaged at 17 1") and returns the damaged frames concealed.
TEST_F(CameraErrors, ADamagedVideoIsAnErrorQuotingFfmpegWhichPrintsNothing) {
  const std::vector<cv::Mat> frames = longer_presses();
  ASSERT_TRUE(write_video(dir_ / "whole.mp4", "mp4v", frames));
  const std::string bytes = read_file(dir_ / "whole.mp4");
  // The index (moov) follows the frames (mdat): the first half has none.
  write_file(dir_ / "no_index.mp4", bytes.substr(0, bytes.size() / 2));
  std::string damaged = bytes;
  const std::size_t frames_at = damaged.find("mdat"), index_at = damaged.find("moov");
  ASSERT_LT(frames_at, index_at);
  for (std::size_t at = frames_at + (index_at - frames_at) / 3; at < frames_at + (index_at - frames_at) / 2; at += 13)
    damaged[at] = static_cast<char>(damaged[at] ^ 0x5A);
  write_file(dir_ / "damaged_frames.mp4", damaged);

  testing::internal::CaptureStderr();
  const std::string no_index = load_error("video: no_index.mp4");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_NE(no_index.find("no_index.mp4 cannot be opened: not a video OpenCV's FFmpeg can decode (FFmpeg says '"),
            std::string::npos)
      << no_index;
  EXPECT_NE(no_index.find("moov atom not found"), std::string::npos) << no_index;

  testing::internal::CaptureStderr();
  const std::string in_frames = run_error<InputError>("video: damaged_frames.mp4");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_NE(in_frames.find("damaged_frames.mp4 is damaged at or before its frame "), std::string::npos) << in_frames;
  EXPECT_NE(in_frames.find(" of " + std::to_string(frames.size()) + " (corrupt or cut short): FFmpeg says '[mpeg4 @ "),
            std::string::npos)
      << in_frames;
}

// A recording cut short (a camera unplugged while it was written) ends the
// run with an error naming the file and how far it got; the frames before
// the cut were processed. The cut falls inside a frame, which FFmpeg finds
// damaged.
TEST_F(CameraErrors, AVideoCutShortIsAnErrorNamingTheFile) {
  const std::vector<cv::Mat> frames = longer_presses();
  ASSERT_TRUE(write_video(dir_ / "whole.avi", "MJPG", frames));
  const std::string bytes = read_file(dir_ / "whole.avi");
  write_file(dir_ / "cut.avi", bytes.substr(0, bytes.size() / 2));
  const std::string e = run_error<InputError>("video: cut.avi");
  EXPECT_NE(e.find("cut.avi is damaged at or before its frame "), std::string::npos) << e;
  EXPECT_NE(e.find(" of " + std::to_string(frames.size()) + " (corrupt or cut short): FFmpeg says '[mjpeg @ "),
            std::string::npos)
      << e;
}

TEST_F(CameraErrors, FramesOfAnotherSizeAreRefusedNamingBoth) {
  ASSERT_TRUE(write_video(dir_ / "presses.mkv", "FFV1", press_frames()));
  const std::string e = load_error("video: presses.mkv, size: [640, 480]");
  EXPECT_NE(e.find("is 320 x 240 px, not the 640 x 480 px of 'size'"), std::string::npos) << e;
  // An image file of a recording that differs from the size asked.
  write_frame_files(dir_.path(), {cv::Mat(240, 320, CV_8UC3, cv::Scalar::all(9)), cv::Mat(120, 160, CV_8UC3, cv::Scalar::all(9))});
  const std::string later = run_error<InputError>("frames: 'frame_{iteration}.png', size: [320, 240]");
  EXPECT_NE(later.find("frame_1.png is 160 x 120 px, not the 320 x 240 px of 'size'"), std::string::npos) << later;
}

TEST_F(CameraErrors, ExactlyOneSourceAndOneReference) {
  write_frame_files(dir_.path(), {cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(9))});
  EXPECT_NE(load_error("").find("give exactly one of video, frames and device"), std::string::npos);
  EXPECT_NE(load_error("frames: 'frame_{iteration}.png', device: '0'").find("give exactly one"), std::string::npos);
  EXPECT_NE(load_error("frames: 'frame_{iteration}.png', reference_frames: 0").find("the reference is either"),
            std::string::npos);
  EXPECT_NE(load_error("frames: 'frame_{iteration}.png', pixel_format: MJPG").find("pixel_format is asked of a device"),
            std::string::npos);
  // One frame, taken as the reference, leaves nothing to process.
  const std::string e = run_error<InputError>("frames: 'frame_{iteration}.png', reference_frames: 2");
  EXPECT_NE(e.find("ends within its reference frames"), std::string::npos) << e;
}

}  // namespace

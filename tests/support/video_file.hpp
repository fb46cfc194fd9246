// Frames as a video file, as a camera test streams it: OpenCV's FFmpeg
// backend, BGR frames (grey ones converted). Compiled into the tests that
// write videos (they link opencv_videoio), not into touchcloud_test_support.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::test {

// A video of `frames` at `fps` in the codec `fourcc` (FFV1, MJPG, ...);
// false when this OpenCV cannot write that codec.
bool write_video_file(const std::filesystem::path& file, const std::string& fourcc, const std::vector<cv::Mat>& frames,
                      double fps);

}  // namespace touchcloud::test

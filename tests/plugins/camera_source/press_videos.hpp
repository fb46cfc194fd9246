// Simulated presses as a camera would deliver them: the GelSight-type
// sample dataset's rendered images (its no-contact reference first), as
// PNG files and as video files in a codec OpenCV's FFmpeg backend writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::test {

// reference.png, then every press image of sample_clouds/tactile_nets_sample
// (320 x 240 BGR).
std::vector<cv::Mat> press_frames();
// frame_0.png, frame_1.png, ... in `dir`.
void write_frame_files(const std::filesystem::path& dir, const std::vector<cv::Mat>& frames);
// A video of `frames` at 25 frames/s; false when this OpenCV cannot write the codec.
bool write_video(const std::filesystem::path& file, const std::string& fourcc, const std::vector<cv::Mat>& frames);

}  // namespace touchcloud::test

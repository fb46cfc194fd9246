// A rendered calibration set written as image files in the layout
// pipelines/calibrate_from_images.yaml reads: air/ and press/, each with
// left_N.png and right_N.png. Tests that include this link
// touchcloud::simulation and opencv_imgcodecs.
#pragma once

#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "touchcloud/simulation/board/calibration_images.hpp"

namespace touchcloud::test {

inline void write_image(const std::filesystem::path& file, const cv::Mat& image) {
  std::filesystem::create_directories(file.parent_path());
  if (!cv::imwrite(file.string(), image)) throw std::runtime_error("cannot write " + file.string());
}

inline void write_image_pairs(const std::filesystem::path& folder,
                              const std::vector<simulation::StereoImages>& pairs) {
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    write_image(folder / ("left_" + std::to_string(i) + ".png"), pairs[i].left);
    write_image(folder / ("right_" + std::to_string(i) + ".png"), pairs[i].right);
  }
}

}  // namespace touchcloud::test

// Training samples from a dense stereo dataset folder (layout:
// touchcloud/io/stereo_dataset.hpp): every pair's images, and its contact
// mask and left disparity truth where the folder lists them. Torch-free
// (OpenCV images); tensor_batch() in torch_io.hpp turns them into batches.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/types/rectified_stereo.hpp"

namespace touchcloud::learning {

struct StereoSample {
  cv::Mat left, right;         // CV_8UC3
  cv::Mat contact_mask;        // CV_8UC1 (255: contact) or empty when the row lists none
  cv::Mat disparity_left_px;   // CV_32FC1 truth, or empty
  cv::Mat valid_left;          // CV_8UC1, with disparity_left_px
  long index = 0;
  std::string where;           // "DIR/index.csv:LINE", for messages
};

struct StereoSamples {
  std::vector<StereoSample> samples;
  RectifiedStereo camera;
  std::filesystem::path index_file;
};

// Reads every row of the dataset whose index is `index_file` (DIR/index.csv).
// InputError naming the file for a missing or malformed index or camera, a
// dataset without pairs, an unreadable image, or an image whose size or
// type differs from camera.yaml's.
StereoSamples read_stereo_samples(const std::filesystem::path& index_file);

}  // namespace touchcloud::learning

// Reading one sample of a tactile dataset folder
// (touchcloud/io/tactile_dataset.hpp) with the layout's checks, for the
// reader stage and for the networks' training stage alike.
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "touchcloud/io/tactile_dataset.hpp"

namespace touchcloud::io {

// One image of the dataset whose dataset.yaml is `info_file`: InputError
// naming the file when it cannot be read, is not of `type` (CV_8UC3 images,
// CV_32FC1 heights, CV_8UC1 masks) or not of dataset.yaml's size.
cv::Mat read_dataset_image(const std::filesystem::path& file, int type, const TactileDatasetInfo& info,
                           const std::string& info_file);

struct SampleTruth {
  cv::Mat height_mm;     // CV_32FC1, never NaN or infinite
  cv::Mat contact_mask;  // CV_8UC1, 255: contact (the sample's mask, or height > the dataset's threshold)
};
// The sample's height map and contact mask; InputError naming the file for a
// height map with NaN or infinity.
SampleTruth read_sample_truth(const TactileSample& sample, const TactileDatasetInfo& info,
                              const std::string& info_file);

}  // namespace touchcloud::io

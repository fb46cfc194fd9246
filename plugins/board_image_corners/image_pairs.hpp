// The left/right image files of a calibration set: a pair of file patterns
// where '{iteration}' stands for 0, 1, 2, ...; the first number without a
// left file ends the set.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace touchcloud::board_image_corners {

struct ImagePair {
  std::filesystem::path left, right;
};

// Every pair the patterns name (one pair when they hold no '{iteration}').
// InputError naming the file for: no left image 0, a left image without its
// right one, or a right image beyond the last left one.
std::vector<ImagePair> list_image_pairs(const std::string& left_pattern, const std::string& right_pattern);

// The image as 8-bit grey; InputError naming the file when it cannot be read.
cv::Mat read_grey_image(const std::filesystem::path& file);

}  // namespace touchcloud::board_image_corners

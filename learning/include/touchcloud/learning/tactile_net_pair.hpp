// ContactNet and TactileDepthNet loaded together from their checkpoints for
// inference: one tactile image and its reference in, the contact
// probability and the height map (mm) out. Includes torch.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "touchcloud/learning/tactile_nets.hpp"

namespace touchcloud::learning {

// What a TactileDepthNet checkpoint says of the sensor it was trained for
// (training fields "sensor", "mm_per_px", "gel_thickness_mm": the dataset's).
struct TactileSensorFields {
  std::string sensor;
  double mm_per_px = 0, gel_thickness_mm = 0;
};

// The headers of the two checkpoints, checked: InputError naming the file
// when one is missing or not a checkpoint, is of another architecture
// (naming both), or when the two are for different input sizes (naming both).
struct TactileNetHeaders {
  TactileNetShape contact, depth;
  TactileSensorFields sensor;
  static TactileNetHeaders read(const std::filesystem::path& contact_file, const std::filesystem::path& depth_file);
};

// A training field's value, if the header has it.
std::optional<std::string> training_field(const CheckpointHeader& header, const std::string& name);

struct TactilePrediction {
  cv::Mat contact_probability;  // CV_32FC1 in [0, 1]
  cv::Mat height_mm;            // CV_32FC1
};

class TactileNetPair {
 public:
  // Reads and loads both (TactileNetHeaders::read's refusals; InputError
  // naming the file for weights that do not load).
  TactileNetPair(const std::filesystem::path& contact_file, const std::filesystem::path& depth_file);
  // 8-bit BGR image and reference of the networks' input size (the caller checks).
  TactilePrediction predict(const cv::Mat& image, const cv::Mat& reference);
  const TactileNetHeaders& headers() const { return headers_; }

 private:
  TactileNetHeaders headers_;
  ContactNet contact_{nullptr};
  TactileDepthNet depth_{nullptr};
};

}  // namespace touchcloud::learning

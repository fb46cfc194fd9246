// Fast, seeded Gaussian noise on 8-bit images, and blur.
//
// A frame holds about 1.8 million pixels; drawing each from
// std::normal_distribution costs more than the whole rendering budget. Here
// 16 random bits index a table of the Gaussian's inverse CDF at the midpoints
// of 65536 equal-probability bins (the tails are cut at about 4.3 sigma), and
// one 64-bit draw (splitmix64) serves four pixels. Grey levels are integers,
// so round(I + noise) = I + round(noise): the table holds rounded values.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/simulation/render/counter_random.hpp"

namespace touchcloud::simulation {

class ImageNoise {
 public:
  explicit ImageNoise(double sigma_grey);
  double sigma_grey() const { return sigma_; }
  // Adds noise to every pixel of a CV_8UC1 image (rounded, saturated).
  // The same seed gives the same noise.
  void apply(cv::Mat& image, std::uint64_t seed) const;

 private:
  double sigma_;
  std::vector<std::int16_t> offsets_;  // 65536 noise values, rounded to grey levels
};

// Gaussian blur of a grey image (OpenCV), sigma in pixels.
void blur_image(cv::Mat& image, double sigma_px);

}  // namespace touchcloud::simulation

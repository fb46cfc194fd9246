#include "touchcloud/simulation/render/image_noise.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/special_functions/erf.hpp>
#include <opencv2/imgproc.hpp>

namespace touchcloud::simulation {

ImageNoise::ImageNoise(double sigma_grey) : sigma_(sigma_grey), offsets_(65536) {
  for (std::size_t i = 0; i < offsets_.size(); ++i) {
    const double u = (static_cast<double>(i) + 0.5) / 65536.0;  // in (0, 1)
    const double z = std::sqrt(2.0) * boost::math::erf_inv(2.0 * u - 1.0);
    offsets_[i] = static_cast<std::int16_t>(std::clamp(std::lround(sigma_ * z), -255l, 255l));
  }
}

void ImageNoise::apply(cv::Mat& image, std::uint64_t seed) const {
  CV_Assert(image.type() == CV_8UC1);
  std::uint64_t state = seed;
  for (int y = 0; y < image.rows; ++y) {
    auto* row = image.ptr<std::uint8_t>(y);
    int x = 0;
    for (; x + 4 <= image.cols; x += 4) {
      state += kGoldenGamma;
      std::uint64_t bits = mix64(state);
      for (int k = 0; k < 4; ++k, bits >>= 16)
        row[x + k] = static_cast<std::uint8_t>(std::clamp(row[x + k] + offsets_[bits & 0xFFFF], 0, 255));
    }
    for (; x < image.cols; ++x) {
      state += kGoldenGamma;
      row[x] = static_cast<std::uint8_t>(std::clamp(row[x] + offsets_[mix64(state) & 0xFFFF], 0, 255));
    }
  }
}

void blur_image(cv::Mat& image, double sigma_px) { cv::GaussianBlur(image, image, cv::Size(0, 0), sigma_px); }

}  // namespace touchcloud::simulation

#include "touchcloud/simulation/render/colour_texture.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "touchcloud/simulation/render/counter_random.hpp"

namespace touchcloud::simulation {

namespace {
constexpr double kGelWhite = 235.0;  // the bare gel's grey under the LED ring
constexpr int kTexelsPerFeature = 8;
}  // namespace

ColourTexture::ColourTexture(const sensor::ColourPatternSpec& spec, double radius_mm)
    : texel_mm_(spec.feature_mm / kTexelsPerFeature) {
  const double half_mm = radius_mm + spec.feature_mm;
  const int cells = static_cast<int>(std::ceil(2 * half_mm / spec.feature_mm)) + 1;
  origin_mm_ = -0.5 * (cells - 1) * spec.feature_mm;
  cv::Mat coarse(cells, cells, CV_32FC3);
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      auto& c = coarse.at<cv::Vec3f>(j, i);
      for (int ch = 0; ch < 3; ++ch)
        c[ch] = static_cast<float>(255.0 * uniform_from(draw_key(spec.seed, {static_cast<std::uint64_t>(j),
                                                                            static_cast<std::uint64_t>(i),
                                                                            static_cast<std::uint64_t>(ch)})));
    }
  // Each cell a block of texels (nearest), then the smoothing: the texel
  // centres of cell k lie around k * feature_mm, as origin_mm_ says.
  cv::Mat fine;
  cv::resize(coarse, fine, cv::Size(), kTexelsPerFeature, kTexelsPerFeature, cv::INTER_NEAREST);
  origin_mm_ -= 0.5 * spec.feature_mm - 0.5 * texel_mm_;
  cv::GaussianBlur(fine, fine, cv::Size(0, 0), kTexelsPerFeature / 3.0, 0, cv::BORDER_REFLECT);
  // The blur pulls colours towards grey: stretch each channel back to full contrast.
  cv::Scalar mean, sd;
  cv::meanStdDev(fine, mean, sd);
  std::vector<cv::Mat> channels;
  cv::split(fine, channels);
  for (int ch = 0; ch < 3; ++ch) {
    const double gain = sd[ch] > 0 ? 60.0 / sd[ch] : 0.0;  // about +-2 sd over the full range
    channels[ch] = (channels[ch] - mean[ch]) * gain + 127.5;
  }
  cv::merge(channels, fine);
  fine = spec.opacity * fine + (1.0 - spec.opacity) * cv::Scalar::all(kGelWhite);
  fine.convertTo(image_, CV_8UC3);  // rounded and saturated
}

}  // namespace touchcloud::simulation

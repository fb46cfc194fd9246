#include "disparity_errors.hpp"

#include <algorithm>
#include <cmath>

namespace touchcloud::disparity_metrics {

void DisparityErrors::add(const cv::Mat& estimate, const cv::Mat& estimate_valid, const cv::Mat& truth,
                          const cv::Mat& truth_valid, const cv::Mat& region) {
  const double thresholds[3] = {1.25, 1.25 * 1.25, 1.25 * 1.25 * 1.25};
  for (int y = 0; y < truth.rows; ++y) {
    const float* d = estimate.ptr<float>(y);
    const float* t = truth.ptr<float>(y);
    const std::uint8_t* dv = estimate_valid.ptr<std::uint8_t>(y);
    const std::uint8_t* tv = truth_valid.ptr<std::uint8_t>(y);
    const std::uint8_t* in = region.empty() ? nullptr : region.ptr<std::uint8_t>(y);
    for (int x = 0; x < truth.cols; ++x) {
      // A truth of 0 px (a point at infinity) has no relative error: not a pixel of the gel.
      if (!tv[x] || t[x] <= 0 || (in && !in[x])) continue;
      ++pixels_;
      if (!dv[x] || d[x] <= 0) continue;
      ++matched_;
      const double e = static_cast<double>(d[x]) - t[x];
      abs_rel_ += std::abs(e) / t[x];
      sq_rel_ += e * e / t[x];
      sq_ += e * e;
      const double log_e = std::log(static_cast<double>(d[x])) - std::log(static_cast<double>(t[x]));
      sq_log_ += log_e * log_e;
      const double ratio = std::max(d[x] / static_cast<double>(t[x]), t[x] / static_cast<double>(d[x]));
      for (int k = 0; k < 3; ++k) below_[k] += ratio < thresholds[k];
    }
  }
}

double DisparityErrors::rmse_px() const { return std::sqrt(mean(sq_)); }
double DisparityErrors::rmse_log() const { return std::sqrt(mean(sq_log_)); }
double DisparityErrors::delta_below(int k) const {
  return pixels_ ? static_cast<double>(below_.at(static_cast<std::size_t>(k - 1))) / pixels_ : 0.0;
}

}  // namespace touchcloud::disparity_metrics

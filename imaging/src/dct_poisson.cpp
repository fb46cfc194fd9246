#include "touchcloud/imaging/dct_poisson.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fftw3.h>

#include "fftw_planner.hpp"

namespace touchcloud::imaging {

DctPoisson::DctPoisson(int width_px, int height_px) : width_(width_px), height_(height_px) {
  if (width_ < 2 || height_ < 2)
    throw std::invalid_argument("Poisson integration needs at least 2 x 2 pixels, not " + std::to_string(width_px) +
                                " x " + std::to_string(height_px));
  buffer_ = static_cast<double*>(fftw_malloc(sizeof(double) * width_ * height_));
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    forward_ = fftw_plan_r2r_2d(height_, width_, buffer_, buffer_, FFTW_REDFT10, FFTW_REDFT10, FFTW_ESTIMATE);
    inverse_ = fftw_plan_r2r_2d(height_, width_, buffer_, buffer_, FFTW_REDFT01, FFTW_REDFT01, FFTW_ESTIMATE);
  }
  if (!forward_ || !inverse_) {
    fftw_free(buffer_);
    throw std::runtime_error("FFTW could not plan a " + std::to_string(width_) + " x " + std::to_string(height_) +
                             " DCT");
  }
  // REDFT10 then REDFT01 scales by 2n per dimension.
  const double scale = 4.0 * width_ * height_;
  eigen_.create(height_, width_, CV_64FC1);
  for (int l = 0; l < height_; ++l)
    for (int k = 0; k < width_; ++k)
      eigen_.at<double>(l, k) =
          scale * (2 * std::cos(M_PI * k / width_) - 2 + 2 * std::cos(M_PI * l / height_) - 2);
}

DctPoisson::~DctPoisson() {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_destroy_plan(static_cast<fftw_plan>(forward_));
  fftw_destroy_plan(static_cast<fftw_plan>(inverse_));
  fftw_free(buffer_);
}

cv::Mat DctPoisson::solve(const cv::Mat& p, const cv::Mat& q) {
  CV_Assert(p.type() == CV_64FC1 && p.rows == height_ && p.cols == width_ - 1);
  CV_Assert(q.type() == CV_64FC1 && q.rows == height_ - 1 && q.cols == width_);
  // Divergence with no flux through the border.
  for (int v = 0; v < height_; ++v) {
    const double* pr = p.ptr<double>(v);
    const double* qr = v + 1 < height_ ? q.ptr<double>(v) : nullptr;
    const double* qu = v > 0 ? q.ptr<double>(v - 1) : nullptr;
    double* out = buffer_ + static_cast<std::size_t>(v) * width_;
    for (int u = 0; u < width_; ++u) {
      double f = 0;
      if (u + 1 < width_) f += pr[u];
      if (u > 0) f -= pr[u - 1];
      if (qr) f += qr[u];
      if (qu) f -= qu[u];
      out[u] = f;
    }
  }
  fftw_execute(static_cast<fftw_plan>(forward_));
  const double* e = eigen_.ptr<double>(0);
  buffer_[0] = 0;  // the constant: mean zero
  for (std::size_t i = 1, n = static_cast<std::size_t>(width_) * height_; i < n; ++i) buffer_[i] /= e[i];
  fftw_execute(static_cast<fftw_plan>(inverse_));
  cv::Mat h(height_, width_, CV_64FC1);
  for (int v = 0; v < height_; ++v) {
    const double* in = buffer_ + static_cast<std::size_t>(v) * width_;
    double* row = h.ptr<double>(v);
    for (int u = 0; u < width_; ++u) row[u] = in[u];
  }
  return h;
}

}  // namespace touchcloud::imaging

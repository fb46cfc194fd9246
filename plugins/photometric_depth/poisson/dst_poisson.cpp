#include "poisson/dst_poisson.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fftw3.h>

#include "poisson/fftw_planner.hpp"

namespace touchcloud::photometric {

DstPoisson::DstPoisson(int width_px, int height_px)
    : width_(width_px), height_(height_px), nx_(width_px - 2), ny_(height_px - 2) {
  if (nx_ < 1 || ny_ < 1)
    throw std::invalid_argument("Poisson integration needs at least 3 x 3 pixels, not " + std::to_string(width_px) +
                                " x " + std::to_string(height_px));
  buffer_ = static_cast<double*>(fftw_malloc(sizeof(double) * nx_ * ny_));
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan_ = fftw_plan_r2r_2d(ny_, nx_, buffer_, buffer_, FFTW_RODFT00, FFTW_RODFT00, FFTW_ESTIMATE);
  }
  if (!plan_) {
    fftw_free(buffer_);
    throw std::runtime_error("FFTW could not plan a " + std::to_string(nx_) + " x " + std::to_string(ny_) + " DST");
  }
  // RODFT00 applied twice scales by 2(n + 1) per dimension.
  const double scale = 4.0 * (nx_ + 1) * (ny_ + 1);
  eigen_.create(ny_, nx_, CV_64FC1);
  for (int l = 0; l < ny_; ++l)
    for (int k = 0; k < nx_; ++k)
      eigen_.at<double>(l, k) =
          scale * (2 * std::cos(M_PI * (k + 1) / (nx_ + 1)) - 2 + 2 * std::cos(M_PI * (l + 1) / (ny_ + 1)) - 2);
}

DstPoisson::~DstPoisson() {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_destroy_plan(static_cast<fftw_plan>(plan_));
  fftw_free(buffer_);
}

cv::Mat DstPoisson::solve(const cv::Mat& p, const cv::Mat& q) {
  CV_Assert(p.type() == CV_64FC1 && p.rows == height_ && p.cols == width_ - 1);
  CV_Assert(q.type() == CV_64FC1 && q.rows == height_ - 1 && q.cols == width_);
  // The divergence of the gradients on the interior: the 5-point Laplacian of H.
  for (int v = 1; v <= ny_; ++v) {
    const double* pr = p.ptr<double>(v);
    const double* qr = q.ptr<double>(v);
    const double* qu = q.ptr<double>(v - 1);
    double* out = buffer_ + static_cast<std::size_t>(v - 1) * nx_;
    for (int u = 1; u <= nx_; ++u) out[u - 1] = pr[u] - pr[u - 1] + qr[u] - qu[u];
  }
  const auto plan = static_cast<fftw_plan>(plan_);
  fftw_execute(plan);
  const double* e = eigen_.ptr<double>(0);
  for (std::size_t i = 0, n = static_cast<std::size_t>(nx_) * ny_; i < n; ++i) buffer_[i] /= e[i];
  fftw_execute(plan);
  cv::Mat h = cv::Mat::zeros(height_, width_, CV_64FC1);
  for (int v = 1; v <= ny_; ++v) {
    const double* in = buffer_ + static_cast<std::size_t>(v - 1) * nx_;
    double* row = h.ptr<double>(v);
    for (int u = 1; u <= nx_; ++u) row[u] = in[u - 1];
  }
  return h;
}

}  // namespace touchcloud::photometric

#include "touchcloud/imaging/dst_poisson.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fftw3.h>

#include "fftw_planner.hpp"

namespace touchcloud::imaging {

DstPoisson::DstPoisson(int width_px, int height_px)
    : width_(width_px), height_(height_px), nx_(width_px - 2), ny_(height_px - 2) {
  if (nx_ < 1 || ny_ < 1)
    throw std::invalid_argument("Poisson integration needs at least 3 x 3 pixels, not " + std::to_string(width_px) +
                                " x " + std::to_string(height_px));
  buffer_ = static_cast<double*>(fftw_malloc(sizeof(double) * nx_ * ny_));
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    const fftw_r2r_kind kind = FFTW_RODFT00;
    plan_ = fftw_plan_many_r2r(1, &nx_, ny_, buffer_, nullptr, 1, nx_, buffer_, nullptr, 1, nx_, &kind, FFTW_ESTIMATE);
  }
  if (!plan_) {
    fftw_free(buffer_);
    throw std::runtime_error("FFTW could not plan " + std::to_string(ny_) + " sine transforms of " +
                             std::to_string(nx_) + " points");
  }
  // Row frequency k turns the 5-point Laplacian into H(l - 1) + d_k H(l) +
  // H(l + 1) down the column, d_k = 2 cos(pi (k + 1) / (nx + 1)) - 4, with
  // H = 0 above the first and below the last interior row.
  inverse_pivot_.create(ny_, nx_, CV_64FC1);
  upper_.create(ny_, nx_, CV_64FC1);
  for (int k = 0; k < nx_; ++k) {
    const double d = 2 * std::cos(M_PI * (k + 1) / (nx_ + 1)) - 4;
    double upper = 0;
    for (int l = 0; l < ny_; ++l) {
      const double pivot = d - upper;  // |d| > 2 keeps every pivot below -1
      inverse_pivot_.at<double>(l, k) = 1 / pivot;
      upper = 1 / pivot;
      upper_.at<double>(l, k) = upper;
    }
  }
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
  // Down every column at once, row by row: forward elimination, then back
  // substitution (the row transform applied twice scales by 2 (nx + 1)).
  const std::size_t n = static_cast<std::size_t>(nx_);
  for (int l = 0; l < ny_; ++l) {
    double* row = buffer_ + l * n;
    const double* above = l > 0 ? row - n : nullptr;
    const double* inverse_pivot = inverse_pivot_.ptr<double>(l);
    for (std::size_t k = 0; k < n; ++k) row[k] = (row[k] - (above ? above[k] : 0.0)) * inverse_pivot[k];
  }
  for (int l = ny_ - 2; l >= 0; --l) {
    double* row = buffer_ + l * n;
    const double* below = row + n;
    const double* upper = upper_.ptr<double>(l);
    for (std::size_t k = 0; k < n; ++k) row[k] -= upper[k] * below[k];
  }
  fftw_execute(plan);
  const double scale = 1.0 / (2.0 * (nx_ + 1));
  for (std::size_t i = 0, size = n * ny_; i < size; ++i) buffer_[i] *= scale;
  cv::Mat h = cv::Mat::zeros(height_, width_, CV_64FC1);
  for (int v = 1; v <= ny_; ++v) {
    const double* in = buffer_ + static_cast<std::size_t>(v - 1) * nx_;
    double* row = h.ptr<double>(v);
    for (int u = 1; u <= nx_; ++u) row[u] = in[u - 1];
  }
  return h;
}

}  // namespace touchcloud::imaging

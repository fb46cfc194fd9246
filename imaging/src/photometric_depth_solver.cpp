#include "touchcloud/imaging/photometric_depth_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <opencv2/imgproc.hpp>

namespace touchcloud::imaging {

PhotometricDepthSolver::PhotometricDepthSolver(sensor::PhotometricCalibration calibration, DepthOptions options)
    : calibration_(std::move(calibration)),
      options_(options),
      p_(calibration_.height_px, calibration_.width_px - 1, CV_64FC1),
      q_(calibration_.height_px - 1, calibration_.width_px, CV_64FC1) {
  // The polynomial's terms r^i g^j b^k in the calibration's order (i, then
  // j, then k; sensor::PhotometricCalibration::monomials).
  for (int i = 0; i <= calibration_.degree; ++i)
    for (int j = 0; i + j <= calibration_.degree; ++j)
      for (int k = 0; i + j + k <= calibration_.degree; ++k) exponents_.push_back({i, j, k});
  exponents_.resize(std::min(exponents_.size(), calibration_.gx.size()));  // as gradient(): gx's terms
  if (options_.border == PoissonBorder::Zero)
    zero_border_ = std::make_unique<DstPoisson>(calibration_.width_px, calibration_.height_px);
  else
    free_border_ = std::make_unique<DctPoisson>(calibration_.width_px, calibration_.height_px);
}

DepthResult PhotometricDepthSolver::solve(const cv::Mat& image, const cv::Mat& reference) {
  DepthResult out;
  gradients(image, reference, out);
  return integrate(std::move(out));
}

DepthResult PhotometricDepthSolver::solve(const cv::Mat& image, const cv::Mat& reference,
                                          const ExcludedPixels& excluded) {
  DepthResult out;
  gradients(image, reference, out);
  excluded_fill_.fill(excluded, {&out.gx, &out.gy});
  return integrate(std::move(out));
}

void PhotometricDepthSolver::gradients(const cv::Mat& image, const cv::Mat& reference, DepthResult& out) {
  const int w = image.cols, h = image.rows;
  gx_.create(h, w, CV_64FC1);
  gy_.create(h, w, CV_64FC1);
  gx_.setTo(0);
  gy_.setTo(0);
  out.gx = gx_;
  out.gy = gy_;
  // The largest channel difference of each pixel, in OpenCV's vectorised
  // passes; most of a frame is flat gel, so the polynomial runs only where
  // it exceeds `flat`.
  cv::absdiff(image, reference, channel_difference_);
  cv::split(channel_difference_, channels_);
  cv::Mat& difference = difference_;
  cv::max(channels_[0], channels_[1], difference);
  cv::max(difference, channels_[2], difference);
  const int flat = static_cast<int>(std::floor(options_.flat_grey));
  const double per_grey = 1.0 / calibration_.scale_grey;
  const int degree = calibration_.degree;
  const std::size_t terms = exponents_.size();
  const double* coefficient_x = calibration_.gx.data();
  const double* coefficient_y = calibration_.gy.data();
  long sloped = 0;
  for (int v = 0; v < h; ++v) {
    const cv::Vec3b* a = image.ptr<cv::Vec3b>(v);
    const cv::Vec3b* b = reference.ptr<cv::Vec3b>(v);
    const std::uint8_t* d = difference.ptr<std::uint8_t>(v);
    double* gx = out.gx.ptr<double>(v);
    double* gy = out.gy.ptr<double>(v);
    for (int u = 0; u < w; ++u) {
      if (d[u] <= flat) continue;
      ++sloped;
      const int db = a[u][0] - b[u][0], dg = a[u][1] - b[u][1], dr = a[u][2] - b[u][2];
      // calibration_.gradient(dr, dg, db), term for term in its order (a
      // call per pixel cost more than the polynomial).
      const double r = dr * per_grey, g = dg * per_grey, bl = db * per_grey;
      double rp[8], gp[8], bp[8];
      rp[0] = gp[0] = bp[0] = 1;
      for (int e = 1; e <= degree; ++e) rp[e] = rp[e - 1] * r, gp[e] = gp[e - 1] * g, bp[e] = bp[e - 1] * bl;
      double x = 0, y = 0;
      for (std::size_t t = 0; t < terms; ++t) {
        const double m = rp[exponents_[t][0]] * gp[exponents_[t][1]] * bp[exponents_[t][2]];
        x += coefficient_x[t] * m;
        y += coefficient_y[t] * m;
      }
      gx[u] = x;
      gy[u] = y;
    }
  }
  out.flat_pixels += static_cast<long>(w) * h - sloped;
}

DepthResult PhotometricDepthSolver::integrate(DepthResult out) {
  const int w = out.gx.cols, h = out.gx.rows;
  const cv::Mat& difference = difference_;
  const int flat = static_cast<int>(std::floor(options_.flat_grey));
  // Pixel-centred gradients to staggered differences in mm per pixel.
  const double pitch = calibration_.mm_per_px;
  for (int v = 0; v < h; ++v) {
    const double* gx = out.gx.ptr<double>(v);
    double* p = p_.ptr<double>(v);
    for (int u = 0; u + 1 < w; ++u) p[u] = 0.5 * (gx[u] + gx[u + 1]) * pitch;
  }
  for (int v = 0; v + 1 < h; ++v) {
    const double* g0 = out.gy.ptr<double>(v);
    const double* g1 = out.gy.ptr<double>(v + 1);
    double* q = q_.ptr<double>(v);
    for (int u = 0; u < w; ++u) q[u] = 0.5 * (g0[u] + g1[u]) * pitch;
  }
  if (zero_border_) {
    zero_border_->solve(p_, q_, height_);
    height_.convertTo(out.height_mm, CV_32FC1);
  } else {
    cv::Mat h = free_border_->solve(p_, q_);
    // Zero where the gel is flat; without any flat pixel, the lowest is zero.
    double offset = 0;
    if (out.flat_pixels > 0) {
      const cv::Mat flat_mask = difference <= flat;
      offset = cv::mean(h, flat_mask)[0];
    } else {
      cv::minMaxLoc(h, &offset);
    }
    h -= offset;
    h.convertTo(out.height_mm, CV_32FC1);
  }
  cv::Mat smoothed;
  cv::blur(difference, smoothed, cv::Size(5, 5));
  out.contact_mask = (out.height_mm > options_.contact_height_mm) & (smoothed > options_.contact_grey);
  return out;
}

}  // namespace touchcloud::imaging

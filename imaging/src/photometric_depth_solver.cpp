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
  if (options_.border == PoissonBorder::Zero)
    zero_border_ = std::make_unique<DstPoisson>(calibration_.width_px, calibration_.height_px);
  else
    free_border_ = std::make_unique<DctPoisson>(calibration_.width_px, calibration_.height_px);
}

DepthResult PhotometricDepthSolver::solve(const cv::Mat& image, const cv::Mat& reference) {
  const int w = image.cols, h = image.rows;
  DepthResult out;
  out.gx = cv::Mat::zeros(h, w, CV_64FC1);
  out.gy = cv::Mat::zeros(h, w, CV_64FC1);
  cv::Mat difference(h, w, CV_8UC1);
  const int flat = static_cast<int>(std::floor(options_.flat_grey));
  for (int v = 0; v < h; ++v) {
    const cv::Vec3b* a = image.ptr<cv::Vec3b>(v);
    const cv::Vec3b* b = reference.ptr<cv::Vec3b>(v);
    double* gx = out.gx.ptr<double>(v);
    double* gy = out.gy.ptr<double>(v);
    std::uint8_t* d = difference.ptr<std::uint8_t>(v);
    for (int u = 0; u < w; ++u) {
      const int db = a[u][0] - b[u][0], dg = a[u][1] - b[u][1], dr = a[u][2] - b[u][2];
      const int largest = std::max({std::abs(db), std::abs(dg), std::abs(dr)});
      d[u] = static_cast<std::uint8_t>(largest);
      if (largest <= flat) {
        ++out.flat_pixels;
        continue;
      }
      const Eigen::Vector2d g = calibration_.gradient(Eigen::Vector3d(dr, dg, db));
      gx[u] = g.x();
      gy[u] = g.y();
    }
  }
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
    zero_border_->solve(p_, q_).convertTo(out.height_mm, CV_32FC1);
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

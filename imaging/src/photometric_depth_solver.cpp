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

namespace {

// The colour difference, per pixel, to the polynomial's gradient: every
// pixel's difference to the reference (its largest channel kept for the
// contact mask and the flat test), and the gradient where it is not flat.
template <typename Polynomial>
long gradient_rows(const cv::Mat& image, const cv::Mat& reference, int flat, double per_grey,
                   const Polynomial& polynomial, cv::Mat& gx_out, cv::Mat& gy_out, cv::Mat& difference) {
  long flat_pixels = 0;
  for (int v = 0; v < image.rows; ++v) {
    const cv::Vec3b* a = image.ptr<cv::Vec3b>(v);
    const cv::Vec3b* b = reference.ptr<cv::Vec3b>(v);
    double* gx = gx_out.ptr<double>(v);
    double* gy = gy_out.ptr<double>(v);
    std::uint8_t* d = difference.ptr<std::uint8_t>(v);
    for (int u = 0; u < image.cols; ++u) {
      const int db = a[u][0] - b[u][0], dg = a[u][1] - b[u][1], dr = a[u][2] - b[u][2];
      const int largest = std::max({std::abs(db), std::abs(dg), std::abs(dr)});
      d[u] = static_cast<std::uint8_t>(largest);
      if (largest <= flat) {
        ++flat_pixels;
        gx[u] = gy[u] = 0;
        continue;
      }
      polynomial(dr * per_grey, dg * per_grey, db * per_grey, gx[u], gy[u]);
    }
  }
  return flat_pixels;
}

// calibration.gradient(r, g, b), term for term in its order (a call per
// pixel cost more than the polynomial): r^i g^j b^k with i, then j, then k
// rising, each product formed as (r^i g^j) b^k, the sums in that order.
struct AnyDegree {
  const std::vector<std::array<int, 3>>& exponents;
  int degree;
  const double* cx;
  const double* cy;
  void operator()(double r, double g, double b, double& x_out, double& y_out) const {
    double rp[8], gp[8], bp[8];
    rp[0] = gp[0] = bp[0] = 1;
    for (int e = 1; e <= degree; ++e) rp[e] = rp[e - 1] * r, gp[e] = gp[e - 1] * g, bp[e] = bp[e - 1] * b;
    double x = 0, y = 0;
    for (std::size_t t = 0; t < exponents.size(); ++t) {
      const double m = rp[exponents[t][0]] * gp[exponents[t][1]] * bp[exponents[t][2]];
      x += cx[t] * m;
      y += cy[t] * m;
    }
    x_out = x;
    y_out = y;
  }
};

// The same sums for a degree known when compiling: its terms unrolled, with
// the same products in the same order (the same bits, three times faster).
template <int Degree>
struct FixedDegree {
  static constexpr int kTerms = (Degree + 1) * (Degree + 2) * (Degree + 3) / 6;
  static constexpr std::array<std::array<int, 3>, kTerms> kExponents = [] {
    std::array<std::array<int, 3>, kTerms> e{};
    int t = 0;
    for (int i = 0; i <= Degree; ++i)
      for (int j = 0; i + j <= Degree; ++j)
        for (int k = 0; i + j + k <= Degree; ++k) e[t++] = {i, j, k};
    return e;
  }();
  const double* cx;
  const double* cy;
  void operator()(double r, double g, double b, double& x_out, double& y_out) const {
    double rp[Degree + 1], gp[Degree + 1], bp[Degree + 1];
    rp[0] = gp[0] = bp[0] = 1;
#pragma GCC unroll 8
    for (int e = 1; e <= Degree; ++e) rp[e] = rp[e - 1] * r, gp[e] = gp[e - 1] * g, bp[e] = bp[e - 1] * b;
    double x = 0, y = 0;
#pragma GCC unroll 40
    for (int t = 0; t < kTerms; ++t) {
      const double m = rp[kExponents[t][0]] * gp[kExponents[t][1]] * bp[kExponents[t][2]];
      x += cx[t] * m;
      y += cy[t] * m;
    }
    x_out = x;
    y_out = y;
  }
};

}  // namespace

void PhotometricDepthSolver::gradients(const cv::Mat& image, const cv::Mat& reference, DepthResult& out) {
  const int w = image.cols, h = image.rows;
  gx_.create(h, w, CV_64FC1);
  gy_.create(h, w, CV_64FC1);
  out.gx = gx_;
  out.gy = gy_;
  difference_.create(h, w, CV_8UC1);
  const int flat = static_cast<int>(std::floor(options_.flat_grey));
  const double per_grey = 1.0 / calibration_.scale_grey;
  const double* cx = calibration_.gx.data();
  const double* cy = calibration_.gy.data();
  const auto rows = [&](const auto& polynomial) {
    out.flat_pixels = gradient_rows(image, reference, flat, per_grey, polynomial, out.gx, out.gy, difference_);
  };
  const bool every_term = exponents_.size() ==
                          static_cast<std::size_t>((calibration_.degree + 1) * (calibration_.degree + 2) *
                                                   (calibration_.degree + 3) / 6);
  if (every_term && calibration_.degree == 2)
    rows(FixedDegree<2>{cx, cy});
  else if (every_term && calibration_.degree == 3)
    rows(FixedDegree<3>{cx, cy});
  else if (every_term && calibration_.degree == 4)
    rows(FixedDegree<4>{cx, cy});
  else
    rows(AnyDegree{exponents_, calibration_.degree, cx, cy});
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

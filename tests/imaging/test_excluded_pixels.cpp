// The fill of excluded pixels (imaging/excluded_pixels.hpp) on fields whose
// fill is known: a plane comes back exactly, and x^2 - y^2 (harmonic, and
// the 5-point Laplacian of it is exactly zero, so the discrete harmonic fill
// is the field itself) comes back within a tenth of the row-by-row start's
// error after the sweeps the window sets (plain Gauss-Seidel, as many sweeps
// as the window is wide, leaves a quarter to two thirds of it).
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "touchcloud/imaging/excluded_pixels.hpp"

namespace touchcloud::imaging {
namespace {

template <typename Field>
cv::Mat make_field(int w, int h, Field field) {
  cv::Mat m(h, w, CV_64FC1);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) m.at<double>(v, u) = field(u, v);
  return m;
}

// A disc `diameter` px wide at (cx, cy), and the window it fits in.
ExcludedPixels disc(int w, int h, int cx, int cy, int diameter) {
  ExcludedPixels out;
  out.mask = cv::Mat::zeros(h, w, CV_8UC1);
  cv::circle(out.mask, {cx, cy}, diameter / 2, cv::Scalar(255), cv::FILLED);
  out.window_px = diameter | 1;
  return out;
}

double largest_error(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  double worst = 0;
  cv::minMaxLoc(cv::abs(a - b), nullptr, &worst, nullptr, nullptr, mask);
  return worst;
}

TEST(ExcludedFill, APlaneComesBackExactly) {
  const auto plane = [](int u, int v) { return 0.3 * u - 0.7 * v + 2; };
  const cv::Mat truth = make_field(64, 48, plane);
  cv::Mat a = truth.clone(), b = truth.clone();
  const ExcludedPixels excluded = disc(64, 48, 30, 20, 15);
  a.setTo(99, excluded.mask);
  b.setTo(-99, excluded.mask);
  ExcludedFill().fill(excluded, {&a, &b});
  EXPECT_LT(largest_error(a, truth, excluded.mask), 1e-9);
  EXPECT_LT(largest_error(b, truth, excluded.mask), 1e-9);
}

TEST(ExcludedFill, AHarmonicFieldIsReachedWithinTheWindowsSweeps) {
  const auto saddle = [](int u, int v) { return 1e-3 * ((u - 20.0) * (u - 20.0) - (v - 30.0) * (v - 30.0)); };
  const cv::Mat truth = make_field(64, 64, saddle);
  for (const int diameter : {9, 19, 31}) {
    const ExcludedPixels excluded = disc(64, 64, 32, 32, diameter);
    cv::Mat filled = truth.clone();
    filled.setTo(0, excluded.mask);
    ExcludedFill().fill(excluded, {&filled});
    // The start the sweeps improve on: along each row, the straight line
    // between the kept pixels either side.
    cv::Mat lines = truth.clone();
    for (int v = 0; v < 64; ++v)
      for (int u = 0; u < 64; ++u)
        if (excluded.mask.at<std::uint8_t>(v, u)) {
          int left = u, right = u;
          while (excluded.mask.at<std::uint8_t>(v, left)) --left;
          while (excluded.mask.at<std::uint8_t>(v, right)) ++right;
          const double t = double(u - left) / (right - left);
          lines.at<double>(v, u) = (1 - t) * truth.at<double>(v, left) + t * truth.at<double>(v, right);
        }
    const double start_error = largest_error(lines, truth, excluded.mask);
    const double error = largest_error(filled, truth, excluded.mask);
    ASSERT_GT(start_error, 1e-3) << diameter << " px";
    EXPECT_LT(error, start_error / 10) << diameter << " px disc: start " << start_error << ", filled " << error;
    EXPECT_TRUE(cv::checkRange(filled));
  }
}

TEST(ExcludedFill, ABlobCutByTheImagesBorderStaysWithinTheKeptValues) {
  const auto plane = [](int u, int v) { return 0.5 * u + 0.25 * v; };
  const cv::Mat truth = make_field(32, 32, plane);
  cv::Mat f = truth.clone();
  const ExcludedPixels excluded = disc(32, 32, 0, 16, 7);  // cut by the left border
  ASSERT_GT(cv::countNonZero(excluded.mask.col(0)), 0);
  f.setTo(1e3, excluded.mask);
  ExcludedFill().fill(excluded, {&f});
  // Filled from the kept pixels beside the blob (0.5 u + 0.25 v over u 0-4,
  // v 13-19: 3.25-6.75), none of the value the blob held.
  double lowest = 0, highest = 0;
  cv::minMaxLoc(f, &lowest, &highest, nullptr, nullptr, excluded.mask);
  EXPECT_GE(lowest, 3.0);
  EXPECT_LE(highest, 7.0);
}

}  // namespace
}  // namespace touchcloud::imaging

// Rendering: dots whose centroid is the sub-pixel centre, the right amount of
// ink, an unevenly lit background, and seeded Gaussian noise.
#include <gtest/gtest.h>

#include <random>

#include "touchcloud/simulation/render/image_noise.hpp"
#include "touchcloud/simulation/render/marker_renderer.hpp"

using namespace touchcloud::simulation;

namespace {

RenderStyle flat_style() {
  RenderStyle s;
  s.background_grey = 200;
  s.vignetting = 0;
  s.gradient = 0;
  s.marker_grey = 40;
  return s;
}

// Ink (background minus image) and its centroid.
double ink(const cv::Mat& image, double background, Eigen::Vector2d& centroid) {
  double total = 0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) {
      const double v = background - image.at<std::uint8_t>(y, x);
      total += v;
      moment += v * Eigen::Vector2d(x, y);
    }
  centroid = moment / total;
  return total;
}

}  // namespace

TEST(MarkerRenderer, DotsSitAtTheirSubPixelCentresWithTheirArea) {
  // Dots in the simulated frames have radii of about 2.5 to 4 px; smaller
  // ones alias more. The bounds include rounding to 8-bit grey levels.
  const MarkerRenderer renderer(64, 48, flat_style());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> sub_pixel(0.0, 1.0);
  for (const auto& [radius, centre_bound, area_bound] :
       std::vector<std::tuple<double, double, double>>{{1.2, 0.04, 0.04}, {2.7, 0.015, 0.006}, {5.0, 0.008, 0.003}}) {
    for (int k = 0; k < 50; ++k) {
      const Eigen::Vector2d centre(30 + sub_pixel(rng), 22 + sub_pixel(rng));
      const cv::Mat image = renderer.render({{centre, radius}});
      Eigen::Vector2d centroid;
      const double total = ink(image, 200, centroid);
      EXPECT_LT((centroid - centre).norm(), centre_bound) << "r " << radius << " at " << centre.transpose();
      EXPECT_NEAR(total / (M_PI * radius * radius * 160.0), 1.0, area_bound) << "r " << radius;
    }
  }
}

TEST(MarkerRenderer, OverlappingDotsTakeTheDarkerValueAndDotsOffTheImageAreClipped) {
  const MarkerRenderer renderer(40, 30, flat_style());
  const cv::Mat one = renderer.render({{{10, 10}, 3}});
  const cv::Mat two = renderer.render({{{10, 10}, 3}, {{10, 10}, 3}});
  EXPECT_EQ(cv::norm(one, two, cv::NORM_INF), 0);
  const cv::Mat edge = renderer.render({{{-1.0, 15.0}, 3}, {{100, 100}, 3}});
  EXPECT_EQ(edge.at<std::uint8_t>(15, 0), 40);
  EXPECT_EQ(edge.at<std::uint8_t>(29, 39), 200);
}

TEST(MarkerRenderer, TheBackgroundIsBrightInTheMiddleAndDarkerAtTheCorners) {
  RenderStyle style;  // defaults: vignetting and a gradient
  const MarkerRenderer renderer(1280, 720, style);
  const cv::Mat& bg = renderer.background();
  const int centre = bg.at<std::uint8_t>(360, 640);
  EXPECT_NEAR(centre, style.background_grey, 2);
  EXPECT_LT(bg.at<std::uint8_t>(0, 0), centre - 40);
  EXPECT_LT(bg.at<std::uint8_t>(0, 0), bg.at<std::uint8_t>(0, 1279));  // lit from the right
  // Smooth: neighbours differ by at most one grey level.
  cv::Mat dx;
  cv::absdiff(bg.colRange(1, 1280), bg.colRange(0, 1279), dx);
  double worst = 0;
  cv::minMaxLoc(dx, nullptr, &worst);
  EXPECT_LE(worst, 1.0);
}

TEST(ImageNoise, IsGaussianWithTheRequestedSigmaAndSeeded) {
  const ImageNoise noise(3.0);
  cv::Mat a(480, 640, CV_8UC1, cv::Scalar(128)), b = a.clone(), c = a.clone();
  noise.apply(a, 42);
  noise.apply(b, 42);
  noise.apply(c, 43);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 0);
  cv::Scalar mean, stddev;
  cv::meanStdDev(a, mean, stddev);
  EXPECT_NEAR(mean[0], 128.0, 0.02);
  EXPECT_NEAR(stddev[0], std::sqrt(9.0 + 1.0 / 12), 0.02);  // plus rounding to grey levels
  // Gaussian tails: about 4.55% beyond 2 sigma (6 grey levels; rounding blurs the edge).
  cv::Mat far = (a > 128 + 6.5) | (a < 128 - 6.5);
  EXPECT_NEAR(cv::countNonZero(far) / double(a.total()), 0.030, 0.006);
}

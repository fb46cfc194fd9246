// The GelSight-type depth solver: Poisson integration is exact on exact
// gradients; a sphere pressed into the simulated gel comes back from its
// rendered image after calibration, and a free border keeps a contact that
// runs off the image.
#include <gtest/gtest.h>

#include <random>

#include "ball_calibration.hpp"
#include "touchcloud/imaging/dct_poisson.hpp"
#include "touchcloud/imaging/dst_poisson.hpp"
#include "touchcloud/imaging/photometric_depth_solver.hpp"
#include "touchcloud/sensor/photometric_calibration.hpp"

using namespace touchcloud;
using namespace touchcloud::test;

namespace {

// The staggered forward differences the solvers take: p across the columns
// (width - 1 of them), q down the rows (height - 1).
std::pair<cv::Mat, cv::Mat> exact_gradients(const cv::Mat& height) {
  const int w = height.cols, h = height.rows;
  return {height.colRange(1, w) - height.colRange(0, w - 1), height.rowRange(1, h) - height.rowRange(0, h - 1)};
}

}  // namespace

TEST(DstPoisson, RecoversAKnownHeightMapFromItsExactGradients) {
  const int w = 320, h = 240;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-0.2, 0.2);
  cv::Mat height = cv::Mat::zeros(h, w, CV_64FC1);
  for (int v = 1; v + 1 < h; ++v)
    for (int u = 1; u + 1 < w; ++u) {
      const double x = (u - 150.0) / 40, y = (v - 110.0) / 30;
      height.at<double>(v, u) = 1.5 * std::exp(-x * x - y * y) + noise(rng);  // a bump and rough texture
    }
  const auto [p, q] = exact_gradients(height);
  imaging::DstPoisson poisson(w, h);
  const cv::Mat solved = poisson.solve(p, q);
  double worst = 0;
  for (int v = 1; v + 1 < h; ++v)
    for (int u = 1; u + 1 < w; ++u) worst = std::max(worst, std::abs(solved.at<double>(v, u) - height.at<double>(v, u)));
  EXPECT_LT(worst, 1e-6) << "worst " << worst << " mm";
  // The plan is reused: a second solve gives the same bits.
  EXPECT_EQ(cv::countNonZero(poisson.solve(p, q) != solved), 0);
  EXPECT_THROW(imaging::DstPoisson(2, 10), std::invalid_argument);
}

// The row transforms and the column systems at their smallest: one interior
// row, one interior column, and a 240-row image's prime-length case above;
// widths whose rows are widened by one (12: 11 interior columns, transformed
// as 12) and by two (23: 21 as 23), with an odd and an even count of rows.
TEST(DstPoisson, RecoversExactGradientsAtTheSmallestSizes) {
  for (const auto& [w, h] : {std::pair{3, 3}, std::pair{7, 3}, std::pair{3, 7}, std::pair{5, 4}, std::pair{12, 5},
                             std::pair{23, 9}, std::pair{23, 4}}) {
    cv::Mat height = cv::Mat::zeros(h, w, CV_64FC1);
    for (int v = 1; v + 1 < h; ++v)
      for (int u = 1; u + 1 < w; ++u) height.at<double>(v, u) = 0.3 * u - 0.2 * v + 0.1 * u * v;
    const auto [p, q] = exact_gradients(height);
    imaging::DstPoisson poisson(w, h);
    const cv::Mat solved = poisson.solve(p, q);
    EXPECT_LT(cv::norm(solved - height, cv::NORM_INF), 1e-12) << w << " x " << h;
  }
}

TEST(DctPoisson, RecoversAnyHeightMapUpToAConstantFromItsExactGradients) {
  const int w = 64, h = 48;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> any(-1.0, 2.0);
  cv::Mat height(h, w, CV_64FC1);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) height.at<double>(v, u) = 0.02 * u + any(rng);  // nothing zero on the border
  const auto [p, q] = exact_gradients(height);
  imaging::DctPoisson poisson(w, h);
  const cv::Mat solved = poisson.solve(p, q);
  const double mean = cv::mean(height)[0];
  double worst = 0;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      worst = std::max(worst, std::abs(solved.at<double>(v, u) - (height.at<double>(v, u) - mean)));
  EXPECT_LT(worst, 1e-6) << "worst " << worst << " mm";
  EXPECT_THROW(imaging::DctPoisson(1, 10), std::invalid_argument);
}

TEST(PhotometricDepth, RecoversASpherePressFromItsImageAfterCalibration) {
  TempDir dir;
  const auto file = calibrate_on_ball(dir, {{-1.5, -1.0}, {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}});
  imaging::PhotometricDepthSolver solver(sensor::load_photometric_calibration(file), {});
  // A held-out press of the ball, elsewhere in the image and less deep.
  simulation::GelSightSimulation sim(ball_scene(), 2);
  press_pad_into(sim, {0.4, -0.3}, 0.5);
  const auto result = solver.solve(sim.render().image, sim.render_reference().image);
  const HeightMap truth = sim.height_truth(0.05);
  double sum2 = 0, worst = 0, peak = 0;
  int n = 0;
  for (int v = 0; v < truth.height_mm.rows; ++v)
    for (int u = 0; u < truth.height_mm.cols; ++u) {
      if (!truth.contact_mask.at<std::uint8_t>(v, u)) continue;
      const double e = result.height_mm.at<float>(v, u) - truth.height_mm.at<float>(v, u);
      sum2 += e * e, ++n;
      worst = std::max(worst, std::abs(e));
      peak = std::max(peak, double(truth.height_mm.at<float>(v, u)));
    }
  ASSERT_GT(n, 1000);
  const double rmse = std::sqrt(sum2 / n);
  const double iou = cv::countNonZero(result.contact_mask & truth.contact_mask) /
                     double(cv::countNonZero(result.contact_mask | truth.contact_mask));
  std::cout << "sphere press " << peak << " mm deep: height RMSE " << rmse << " mm, max error " << worst
            << " mm over " << n << " contact pixels; contact IoU " << iou << "\n";
  EXPECT_LT(rmse, 0.05);
  EXPECT_LT(worst, 0.15);
  EXPECT_GT(iou, 0.8);
}

// The solver evaluates the polynomial itself, pixel by pixel (a call into
// the calibration per pixel cost more than the polynomial): its gradients
// are the calibration's own, to the bit, for every difference a press gives
// (fits of degree 3 and 5).
TEST(PhotometricDepth, PixelGradientsAreTheCalibrationsOwnToTheBit) {
  simulation::GelSightSimulation sim(ball_scene(), 4);
  press_pad_into(sim, {0.4, -0.3}, 0.6);
  const cv::Mat image = sim.render().image, reference = sim.render_reference().image;
  TempDir dir3, dir5;
  const std::vector<Eigen::Vector2d> presses = {{-1.5, -1.0}, {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}};
  const auto degree3 = sensor::load_photometric_calibration(calibrate_on_ball(dir3, presses, 3));
  const auto degree5 = sensor::load_photometric_calibration(calibrate_on_ball(dir5, presses, 5));
  for (const auto* c : {&degree3, &degree5}) {
    imaging::PhotometricDepthSolver solver(*c, {});
    const auto r = solver.solve(image, reference);
    int compared = 0, differing = 0;
    for (int v = 0; v < image.rows; ++v)
      for (int u = 0; u < image.cols; ++u) {
        const cv::Vec3b a = image.at<cv::Vec3b>(v, u), b = reference.at<cv::Vec3b>(v, u);
        const int db = a[0] - b[0], dg = a[1] - b[1], dr = a[2] - b[2];
        if (std::max({std::abs(db), std::abs(dg), std::abs(dr)}) <= 3) continue;  // flat (flat_grey 3)
        const Eigen::Vector2d g = c->gradient(Eigen::Vector3d(dr, dg, db));
        differing += g.x() != r.gx.at<double>(v, u) || g.y() != r.gy.at<double>(v, u);
        ++compared;
      }
    EXPECT_GT(compared, 1000) << "degree " << c->degree;
    EXPECT_EQ(differing, 0) << "degree " << c->degree << ": of " << compared << " pixels";
  }
}

TEST(PhotometricDepth, AFreeBorderKeepsTheHeightOfAContactThatRunsOffTheImage) {
  TempDir dir;
  const auto file = calibrate_on_ball(dir, {{-1.5, -1.0}, {1.5, -1.0}, {-1.0, 1.5}, {1.0, 1.5}});
  // The ball under the pad's edge (half width 9.6 mm): part of the contact lies outside the image.
  simulation::GelSightSimulation sim(ball_scene(), 3);
  press_pad_into(sim, {8.8, 0.0}, 0.5);
  const HeightMap truth = sim.height_truth(0.05);
  int on_border = 0;
  for (int v = 0; v < 240; ++v) on_border += truth.contact_mask.at<std::uint8_t>(v, 0) || truth.contact_mask.at<std::uint8_t>(v, 319);
  ASSERT_GT(on_border, 20);
  auto rmse = [&](imaging::PoissonBorder border) {
    imaging::DepthOptions options;
    options.border = border;
    imaging::PhotometricDepthSolver solver(sensor::load_photometric_calibration(file), options);
    const auto r = solver.solve(sim.render().image, sim.render_reference().image);
    double sum2 = 0;
    int n = 0;
    for (int v = 0; v < 240; ++v)
      for (int u = 0; u < 320; ++u)
        if (truth.contact_mask.at<std::uint8_t>(v, u)) {
          const double e = r.height_mm.at<float>(v, u) - truth.height_mm.at<float>(v, u);
          sum2 += e * e, ++n;
        }
    return std::sqrt(sum2 / n);
  };
  const double zero = rmse(imaging::PoissonBorder::Zero), free = rmse(imaging::PoissonBorder::Free);
  std::cout << "contact off the image (" << on_border << " border rows): height RMSE " << zero << " mm (zero border), "
            << free << " mm (free border)\n";
  EXPECT_LT(free, 0.05);
  EXPECT_GT(zero, 2 * free);
}

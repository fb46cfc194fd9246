// The Table I metrics on a 2 x 2 pair worked out by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "disparity_errors.hpp"

namespace touchcloud::disparity_metrics {
namespace {

struct Pair {
  // Truth 10, 20, 40 px (and an invalid pixel); the estimate is 2.6 px too
  // far, exact, invalid (and valid where the truth is not).
  cv::Mat truth = (cv::Mat_<float>(2, 2) << 10, 20, 40, 50);
  cv::Mat truth_valid = (cv::Mat_<std::uint8_t>(2, 2) << 255, 255, 255, 0);
  cv::Mat estimate = (cv::Mat_<float>(2, 2) << 12.6f, 20, 0, 30);
  cv::Mat estimate_valid = (cv::Mat_<std::uint8_t>(2, 2) << 255, 255, 0, 255);
};

TEST(DisparityErrors, PoolsTheMatchedPixelsAndCountsHolesAgainstTheThresholds) {
  Pair p;
  DisparityErrors e;
  e.add(p.estimate, p.estimate_valid, p.truth, p.truth_valid, {});
  EXPECT_EQ(e.pixels(), 3);
  EXPECT_EQ(e.matched(), 2);
  EXPECT_NEAR(e.coverage(), 2.0 / 3, 1e-12);
  const double err = 12.6f - 10.0;  // the float estimate as stored
  EXPECT_NEAR(e.abs_rel(), (err / 10) / 2, 1e-9);
  EXPECT_NEAR(e.sq_rel(), (err * err / 10) / 2, 1e-9);
  EXPECT_NEAR(e.rmse_px(), std::sqrt(err * err / 2), 1e-9);
  EXPECT_NEAR(e.rmse_log(), std::sqrt(std::pow(std::log(12.6f / 10.0), 2) / 2), 1e-9);
  // 12.6 / 10 = 1.26: above 1.25, below 1.25^2. The hole fails all three.
  EXPECT_NEAR(e.delta_below(1), 1.0 / 3, 1e-12);
  EXPECT_NEAR(e.delta_below(2), 2.0 / 3, 1e-12);
  EXPECT_NEAR(e.delta_below(3), 2.0 / 3, 1e-12);
}

TEST(DisparityErrors, ARegionKeepsOnlyItsPixelsAndPairsPool) {
  Pair p;
  const cv::Mat region = (cv::Mat_<std::uint8_t>(2, 2) << 255, 0, 255, 255);
  DisparityErrors e;
  e.add(p.estimate, p.estimate_valid, p.truth, p.truth_valid, region);
  EXPECT_EQ(e.pixels(), 2);  // the exact pixel is outside, the truth's invalid one does not count
  EXPECT_EQ(e.matched(), 1);
  EXPECT_NEAR(e.abs_rel(), (12.6f - 10.0) / 10, 1e-9);
  e.add(p.estimate, p.estimate_valid, p.truth, p.truth_valid, region);
  EXPECT_EQ(e.pixels(), 4);
  EXPECT_NEAR(e.abs_rel(), (12.6f - 10.0) / 10, 1e-9);
  EXPECT_NEAR(e.delta_below(3), 0.5, 1e-12);
}

TEST(DisparityErrors, NothingMatchedGivesZerosNotNaN) {
  Pair p;
  DisparityErrors e;
  e.add(p.estimate, cv::Mat::zeros(2, 2, CV_8UC1), p.truth, p.truth_valid, {});
  EXPECT_EQ(e.pixels(), 3);
  EXPECT_EQ(e.matched(), 0);
  EXPECT_EQ(e.abs_rel(), 0.0);
  EXPECT_EQ(e.rmse_log(), 0.0);
  EXPECT_EQ(e.delta_below(1), 0.0);
}

}  // namespace
}  // namespace touchcloud::disparity_metrics

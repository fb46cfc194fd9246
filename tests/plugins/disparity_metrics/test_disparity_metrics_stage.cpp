// disparity_metrics as a stage: SGBM-like estimates scored against a truth
// with a contact region, pooled over pairs at finish; and its refusals.
#include <gtest/gtest.h>

#include "stage_harness.hpp"
#include "touchcloud/types/dense_maps.hpp"

namespace touchcloud::test {
namespace {

// A 40 x 30 truth: 60 px everywhere, 62 px in a contact square of 10 x 10.
DenseMapsPtr truth() {
  auto t = std::make_shared<DenseMaps>();
  t->disparity_left_px = cv::Mat(30, 40, CV_32FC1, cv::Scalar(60));
  t->disparity_left_px(cv::Rect(10, 10, 10, 10)).setTo(62);
  t->valid_left = cv::Mat(30, 40, CV_8UC1, cv::Scalar(255));
  t->contact_mask = cv::Mat::zeros(30, 40, CV_8UC1);
  t->contact_mask(cv::Rect(10, 10, 10, 10)).setTo(255);
  return t;
}

// An estimate that misses the contact (60 px there too) and leaves the
// first column invalid, as a block matcher does at the border.
DenseMapsPtr flat_estimate() {
  auto e = std::make_shared<DenseMaps>();
  e->disparity_left_px = cv::Mat(30, 40, CV_32FC1, cv::Scalar(60));
  e->valid_left = cv::Mat(30, 40, CV_8UC1, cv::Scalar(255));
  e->valid_left.col(0).setTo(0);
  return e;
}

TEST(DisparityMetricsStage, ScoresTheContactRegionApartFromTheWholeImage) {
  StageHarness h("disparity_metrics", {});
  h.configure();
  for (int pair = 0; pair < 2; ++pair) h.process({{"disparity", flat_estimate()}, {"truth", truth()}}, {});
  EXPECT_NEAR(h.metric("pair_abs_rel_contact"), 2.0 / 62, 1e-9);
  EXPECT_EQ(h.metric("pair_contact_pixels"), 100);
  h.finish();
  // The contact square is wrong by 2 px everywhere; elsewhere exact.
  EXPECT_NEAR(h.metric("abs_rel_contact"), 2.0 / 62, 1e-9);
  EXPECT_NEAR(h.metric("rmse_contact_px"), 2.0, 1e-9);
  EXPECT_EQ(h.metric("coverage_contact"), 1.0);
  EXPECT_EQ(h.metric("pixels_contact"), 200);
  EXPECT_NEAR(h.metric("coverage_all"), 1.0 - 30.0 / 1200, 1e-12);
  EXPECT_NEAR(h.metric("rmse_all_px"), std::sqrt(4.0 * 100 / (1200 - 30)), 1e-9);
  EXPECT_NEAR(h.metric("delta1_all"), (1200.0 - 30) / 1200, 1e-12);  // 62/60 is within 1.25
}

TEST(DisparityMetricsStage, RefusesMapsOfAnotherSizeOrATruthWithNoValidPixel) {
  StageHarness h("disparity_metrics", {});
  h.configure();
  auto small = std::make_shared<DenseMaps>(*flat_estimate());
  small->disparity_left_px = small->disparity_left_px(cv::Rect(0, 0, 20, 30)).clone();
  EXPECT_EQ(input_error_of([&] { h.process({{"disparity", DenseMapsPtr(small)}, {"truth", truth()}}, {}); }),
            "input 'disparity': the left disparity map is 20 x 30 px; the truth's disparity is 40 x 30 px");
  auto blind = std::make_shared<DenseMaps>(*truth());
  blind->valid_left = cv::Mat::zeros(30, 40, CV_8UC1);
  EXPECT_EQ(input_error_of([&] { h.process({{"disparity", flat_estimate()}, {"truth", DenseMapsPtr(blind)}}, {}); }),
            "input 'truth' (pair 0): the left disparity has no valid pixel");
}

}  // namespace
}  // namespace touchcloud::test

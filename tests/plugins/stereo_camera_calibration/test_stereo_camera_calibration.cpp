// stereo_camera_calibration fed the corners of a 9 x 6 board (10 mm squares)
// projected through two known pinhole cameras 30 mm apart, at poses 150-200 mm
// away and tilted: it gives both cameras' focal lengths and principal points
// and the baseline back; fewer image pairs than min_image_pairs are refused.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "stage_harness.hpp"
#include "touchcloud/error.hpp"
#include "touchcloud/types/board_views.hpp"
#include "touchcloud/types/stereo_cameras.hpp"

using namespace touchcloud;

namespace {

constexpr int kCols = 9, kRows = 6;
constexpr double kSquareMm = 10, kBaselineMm = 30;
const cv::Matx33d kCamera(650, 0, 640, 0, 652, 360, 0, 0, 1);

// The board at `count` poses seen by the left camera and, 30 mm to its right, the right one.
BoardViewsPtr projected_views(int count) {
  std::vector<cv::Point3d> board;
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kCols; ++c) board.emplace_back((c - 4) * kSquareMm, (r - 2.5) * kSquareMm, 0);
  auto views = std::make_shared<BoardViews>();
  views->width_px = 1280, views->height_px = 720, views->cols = kCols, views->rows = kRows;
  for (int k = 0; k < count; ++k) {
    const cv::Vec3d rotation(0.35 * std::sin(1.3 * k), 0.35 * std::cos(0.9 * k + 0.4), 0.2 * std::sin(2.1 * k));
    const cv::Vec3d left_t(8.0 * std::cos(k), 6.0 * std::sin(1.7 * k), 150 + 7.0 * k);
    const cv::Vec3d right_t = left_t - cv::Vec3d(kBaselineMm, 0, 0);
    std::vector<cv::Point2d> left, right;
    cv::projectPoints(board, rotation, left_t, kCamera, cv::noArray(), left);
    cv::projectPoints(board, rotation, right_t, kCamera, cv::noArray(), right);
    auto set = std::make_shared<MarkerSet>();
    for (int i = 0; i < kCols * kRows; ++i) {
      set->left.push_back({{left[i].x, left[i].y}, i, 1.0});
      set->right.push_back({{right[i].x, right[i].y}, i, 1.0});
      set->matches.push_back({i, i, i});
    }
    views->views.push_back({"left_" + std::to_string(k) + ".png", "right_" + std::to_string(k) + ".png", set});
  }
  return views;
}

}  // namespace

TEST(StereoCameraCalibration, KnownCamerasComeBackFromProjectedCorners) {
  test::StageHarness h("stereo_camera_calibration", {{"lens_model", std::string("none")}});
  h.configure();
  const auto cameras = h.process_one<StereoCamerasPtr>({{"views", projected_views(8)}}, "cameras");
  for (const auto* camera : {&cameras->left, &cameras->right}) {
    EXPECT_NEAR(camera->fx_px, 650, 0.5);
    EXPECT_NEAR(camera->fy_px, 652, 0.5);
    EXPECT_NEAR(camera->cx_px, 640, 0.5);
    EXPECT_NEAR(camera->cy_px, 360, 0.5);
  }
  EXPECT_NEAR(cameras->right_from_left.translation().norm(), kBaselineMm, 0.05);
  EXPECT_LT(h.metric("rms_px"), 0.01);  // exact projections
}

TEST(StereoCameraCalibration, FewerImagePairsThanAskedForAreRefused) {
  test::StageHarness h("stereo_camera_calibration", {{"min_image_pairs", std::int64_t{4}}});
  h.configure();
  try {
    h.process_one<StereoCamerasPtr>({{"views", projected_views(3)}}, "cameras");
    FAIL() << "three image pairs accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("3 image pairs of the board; stereo calibration needs at least 4"),
              std::string::npos)
        << e.what();
  }
}

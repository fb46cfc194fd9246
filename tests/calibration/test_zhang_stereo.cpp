// Zhang's method on corners found in rendered images of a board in air:
// intrinsics within 0.5 % of the true cameras', the right camera's pose close
// to the truth, a small residual for every image pair; a view that does not
// fit the others is refused by name.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/calibration/zhang_stereo.hpp"
#include "touchcloud/imaging/chessboard_corners.hpp"
#include "touchcloud/simulation/board/calibration_images.hpp"

using namespace touchcloud;
using calibration::calibrate_stereo;

namespace {

struct AirSet {
  sensor::GelStereoSensor truth;
  BoardViews views;
};

// `pairs` rendered pairs of a 9 x 6 board in air, 1 grey level of noise, corners found as the stage finds them.
AirSet air_set(int pairs, std::uint64_t seed) {
  AirSet set{sensor::load_gelstereo_sensor(test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml"), {}};
  // Unlike the sample sensor's, the right lens differs from the left, and the cameras are not parallel.
  set.truth.cameras.right.fx_px = 660.0;
  set.truth.cameras.right.fy_px = 659.0;
  set.truth.cameras.right.cx_px = 640.0;
  set.truth.cameras.right.cy_px = 360.0;
  set.truth.cameras.right.distortion = {-0.04, 0.015, -0.0004, 0.0002, 0.0};
  set.truth.cameras.right_from_left.linear() =
      Eigen::AngleAxisd(1.0 * M_PI / 180, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  simulation::CalibrationImageOptions options;
  options.air_pairs = pairs;
  options.press_pairs = 0;
  std::mt19937_64 rng(seed);
  const auto images = simulation::render_calibration_images(set.truth, options, rng);
  set.views.width_px = 1280;
  set.views.height_px = 720;
  set.views.cols = options.air_board.cols;
  set.views.rows = options.air_board.rows;
  for (std::size_t i = 0; i < images.air.size(); ++i) {
    auto markers = std::make_shared<MarkerSet>();
    const auto left = imaging::find_board_corners(images.air[i].left, options.air_board, {});
    const auto right = imaging::find_board_corners(images.air[i].right, options.air_board, {});
    EXPECT_TRUE(left && right) << "pair " << i;
    if (!left || !right) continue;
    for (int id = 0; id < options.air_board.corner_count(); ++id) {
      markers->left.push_back({(*left)[static_cast<std::size_t>(id)], id, 1.0});
      markers->right.push_back({(*right)[static_cast<std::size_t>(id)], id, 1.0});
      markers->matches.push_back({id, id, id});
    }
    set.views.views.push_back({"left_" + std::to_string(i) + ".png", "right_" + std::to_string(i) + ".png", markers});
  }
  return set;
}

double percent(double estimate, double truth) { return 100 * std::abs(estimate - truth) / std::abs(truth); }

void expect_intrinsics_within(const optics::CameraIntrinsics& e, const optics::CameraIntrinsics& t, double pct,
                              const char* side) {
  std::cout << side << ": fx " << percent(e.fx_px, t.fx_px) << " %, fy " << percent(e.fy_px, t.fy_px) << " %, cx "
            << percent(e.cx_px, t.cx_px) << " %, cy " << percent(e.cy_px, t.cy_px) << " % off; k1 " << e.distortion.k1
            << " (true " << t.distortion.k1 << ")\n";
  EXPECT_LT(percent(e.fx_px, t.fx_px), pct) << side;
  EXPECT_LT(percent(e.fy_px, t.fy_px), pct) << side;
  EXPECT_LT(percent(e.cx_px, t.cx_px), pct) << side;
  EXPECT_LT(percent(e.cy_px, t.cy_px), pct) << side;
  EXPECT_NEAR(e.distortion.k1, t.distortion.k1, 0.01) << side;
  EXPECT_EQ(e.width_px, t.width_px);
}

}  // namespace

TEST(ZhangStereo, RecoversBothCamerasAndTheirPoseFromRenderedImages) {
  const AirSet set = air_set(12, 21);
  const sensor::Checkerboard board{9, 6, 10.0};
  const auto r = calibrate_stereo(set.views, board, {});
  expect_intrinsics_within(r.cameras.left, set.truth.cameras.left, 0.5, "left");
  expect_intrinsics_within(r.cameras.right, set.truth.cameras.right, 0.5, "right");
  const Eigen::Isometry3d& t = set.truth.cameras.right_from_left;
  const double translation_mm = (r.cameras.right_from_left.translation() - t.translation()).norm();
  const double rotation_deg =
      Eigen::AngleAxisd(r.cameras.right_from_left.linear() * t.linear().transpose()).angle() * 180 / M_PI;
  std::cout << "right_from_left: " << translation_mm << " mm, " << rotation_deg << " deg off; RMS " << r.rms_px
            << " px\n";
  EXPECT_LT(translation_mm, 0.2);
  EXPECT_LT(rotation_deg, 0.05);
  ASSERT_EQ(r.views.size(), 12u);
  for (const auto& v : r.views) {
    EXPECT_GT(v.left_rms_px, 0.0) << v.left_file;
    EXPECT_LT(v.left_rms_px, 0.15) << v.left_file;
    EXPECT_LT(v.right_rms_px, 0.15) << v.right_file;
  }
  EXPECT_EQ(r.views[3].left_file, "left_3.png");
  EXPECT_LT(r.rms_px, 0.15);
}

TEST(ZhangStereo, AViewThatDoesNotFitIsRefusedByName) {
  AirSet set = air_set(6, 22);
  // Corners 0 and 1 of one view's left image swapped: a wrong detection.
  auto markers = std::make_shared<MarkerSet>(*set.views.views[4].corners);
  std::swap(markers->left[0].centre_px, markers->left[1].centre_px);
  set.views.views[4].corners = markers;
  try {
    calibrate_stereo(set.views, {9, 6, 10.0}, {});
    FAIL() << "a view with swapped corners was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("images left_4.png, right_4.png: reprojection RMS"), std::string::npos)
        << e.what();
  }
}

TEST(ZhangStereo, TooFewViewsOrAnotherBoardAreRefused) {
  const AirSet set = air_set(3, 23);
  EXPECT_THROW(calibrate_stereo(set.views, {9, 6, 10.0}, {}), InputError);  // 3 < min_views 4
  calibration::StereoCalibrationOptions three;
  three.min_views = 3;
  EXPECT_NO_THROW(calibrate_stereo(set.views, {9, 6, 10.0}, three));
  EXPECT_THROW(calibrate_stereo(set.views, {7, 6, 10.0}, three), InputError);
}

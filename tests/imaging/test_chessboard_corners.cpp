// Corners found in rendered images land on the true corners' pixels, by id,
// whichever way the board is turned in the image; in air through a
// distorting lens, and pressed into the gel through the plate.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "touchcloud/imaging/chessboard_corners.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"
#include "touchcloud/simulation/board/board_image.hpp"
#include "touchcloud/simulation/board/board_press.hpp"

using namespace touchcloud;
using namespace touchcloud::simulation;
using imaging::find_board_corners;

namespace {

constexpr double kDeg = M_PI / 180.0;

sensor::GelStereoSensor true_sensor() {
  return sensor::load_gelstereo_sensor(test::source_dir() / "sample_clouds/gelstereo_palm2/sensor_true.yaml");
}

// A board facing the camera 160 mm away, turned by `spin_deg` in its plane and tilted 20 deg.
BoardPlacement facing(const sensor::Checkerboard& board, double spin_deg) {
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(20 * kDeg, Eigen::Vector3d(1, 1, 0).normalized()) *
                             Eigen::AngleAxisd(spin_deg * kDeg, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  BoardPlacement p;
  p.along_cols = r.col(0);
  p.along_rows = r.col(1);
  p.corner0_mm = Eigen::Vector3d(15, 0, 160) -
                 0.5 * board.square_mm * ((board.cols - 1) * p.along_cols + (board.rows - 1) * p.along_rows);
  return p;
}

// Largest distance between found and true pixels, corner by corner.
double worst_error_px(const std::vector<Eigen::Vector2d>& found, const BoardCamera& camera,
                      const std::vector<Eigen::Vector3d>& corners) {
  EXPECT_EQ(found.size(), corners.size());
  double worst = 0;
  for (std::size_t id = 0; id < std::min(found.size(), corners.size()); ++id)
    worst = std::max(worst, (found[id] - *camera.pixel(corners[id])).norm());
  return worst;
}

}  // namespace

TEST(ChessboardCorners, FoundInAirAtTheTruePixelsWhicheverWayTheBoardIsTurned) {
  const auto truth = true_sensor();
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const sensor::Checkerboard board{9, 6, 10.0};
  const BoardCamera camera = camera_in_air(rig.camera(optics::StereoSide::Left), Eigen::Isometry3d::Identity());
  std::mt19937_64 rng(5);
  // 180 deg: OpenCV finds the grid from the other end; 90 deg: cols run down
  // the image. Each must come back in the board's own order.
  for (double spin : {0.0, 30.0, 90.0, 180.0, 250.0}) {
    const auto placement = facing(board, spin);
    const cv::Mat image = render_board(camera, board, placement, {}, rng);
    const auto found = find_board_corners(image, board, {});
    ASSERT_TRUE(found) << "spin " << spin;
    const double worst = worst_error_px(*found, camera, placed_corners(board, placement));
    std::cout << "spin " << spin << " deg: worst corner " << worst << " px off\n";
    EXPECT_LT(worst, 0.15) << "spin " << spin;
  }
}

TEST(ChessboardCorners, SectorBasedDetectorAgrees) {
  const auto truth = true_sensor();
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const sensor::Checkerboard board{9, 6, 10.0};
  const BoardCamera camera = camera_in_air(rig.camera(optics::StereoSide::Left), Eigen::Isometry3d::Identity());
  std::mt19937_64 rng(6);
  const auto placement = facing(board, 180.0);
  const cv::Mat image = render_board(camera, board, placement, {}, rng);
  const auto found = find_board_corners(image, board, {imaging::ChessboardDetector::SectorBased, 5});
  ASSERT_TRUE(found);
  EXPECT_LT(worst_error_px(*found, camera, placed_corners(board, placement)), 0.15);
}

TEST(ChessboardCorners, FoundThroughThePlateAtTheTrueRefractedPixels) {
  const auto truth = true_sensor();
  const auto rig = sensor::make_stereo_rig(truth, true, true);
  const sensor::Checkerboard board{6, 5, 3.5};
  const Eigen::Isometry3d left_from_sensor = truth.sensor_from_left_camera().inverse();
  BoardPose pose;
  pose.tilt_deg = {15, -10};
  pose.depth_mm = 9;
  pose.spin_deg = 170;  // upside down in the image
  const auto corners_sensor = board_corners_sensor(board, pose, truth.gel.radius_mm());
  BoardPlacement placement;
  placement.corner0_mm = left_from_sensor * corners_sensor[0];
  placement.along_cols = left_from_sensor.linear() * (corners_sensor[1] - corners_sensor[0]).normalized();
  placement.along_rows = left_from_sensor.linear() * (corners_sensor[6] - corners_sensor[0]).normalized();
  std::mt19937_64 rng(7);
  for (auto side : {optics::StereoSide::Left, optics::StereoSide::Right}) {
    const auto camera = camera_through_plate(rig, side, left_from_sensor, truth.gel.radius_mm());
    const auto found = find_board_corners(render_board(camera, board, placement, {}, rng), board, {});
    ASSERT_TRUE(found) << optics::to_string(side);
    const double worst = worst_error_px(*found, camera, placed_corners(board, placement));
    std::cout << optics::to_string(side) << " through the plate: worst corner " << worst << " px off\n";
    EXPECT_LT(worst, 0.15);
  }
}

TEST(ChessboardCorners, NoBoardAndAWrongBoardSizeFindNothing) {
  const auto rig = sensor::make_stereo_rig(true_sensor(), true, true);
  const sensor::Checkerboard board{9, 6, 10.0};
  const BoardCamera camera = camera_in_air(rig.camera(optics::StereoSide::Left), Eigen::Isometry3d::Identity());
  std::mt19937_64 rng(8);
  const cv::Mat blank(720, 1280, CV_8UC1, cv::Scalar(110));
  EXPECT_FALSE(find_board_corners(blank, board, {}));
  const cv::Mat image = render_board(camera, board, facing(board, 0), {}, rng);
  EXPECT_FALSE(find_board_corners(image, {8, 5, 10.0}, {}));
}

TEST(ChessboardCorners, ABoardThatLooksTheSameTurnedIsRefused) {
  EXPECT_THROW(imaging::require_oriented_board({8, 6, 4.0}), InputError);
  EXPECT_NO_THROW(imaging::require_oriented_board({9, 6, 4.0}));
}

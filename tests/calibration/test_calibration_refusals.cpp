// What the plate solver refuses, and how it says so: flat presses only
// (mu_silicone not determined), too few corners per press or in all, a board
// that does not fit the corners, corner ids off the board.
#include <gtest/gtest.h>

#include "calibration_fixture.hpp"
#include "touchcloud/calibration/plate_calibration.hpp"
#include "touchcloud/error.hpp"

using namespace touchcloud;
using touchcloud::test::kBoard;

namespace {

std::string refusal(const optics::StereoRig& rig, const calibration::Checkerboard& board,
                    const std::vector<calibration::PressCorners>& presses,
                    const calibration::PlateCalibrationOptions& options = {}) {
  try {
    calibration::calibrate_plate(rig, board, presses, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "calibration accepted the presses";
  return {};
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

class CalibrationRefusals : public ::testing::Test {
 protected:
  sensor::GelStereoSensor truth_ = test::true_sensor();
  optics::StereoRig nominal_ = sensor::make_stereo_rig(test::nominal_sensor(), true, true);
  std::mt19937_64 rng_{7};
};

TEST_F(CalibrationRefusals, FlatPressesOnlyAreRefusedAsNotDeterminingMuSilicone) {
  // Boards parallel to the true plate: about 2.5 deg from the nominal one.
  auto poses = test::flat_poses(6);
  for (auto& p : poses) p.tilt_deg = Eigen::Vector2d(0, 0);
  const auto presses = test::simulate_presses(truth_, poses, 0.1, rng_);
  const std::string why = refusal(nominal_, kBoard, presses);
  EXPECT_TRUE(has(why, "flat presses")) << why;
  EXPECT_TRUE(has(why, "mu_silicone")) << why;
  EXPECT_TRUE(has(why, "all 6 boards")) << why;

  // With the tilt check off, the estimate's spread gives them away: with
  // 0.1 px noise mu_silicone's 1-sigma is several hundredths.
  calibration::PlateCalibrationOptions no_tilt_check;
  no_tilt_check.min_board_tilt_deg = 0;
  const std::string why2 = refusal(nominal_, kBoard, presses, no_tilt_check);
  EXPECT_TRUE(has(why2, "do not determine the plate")) << why2;
  // Without noise even flat presses determine the plate (the refraction is
  // not exactly a depth scaling): what makes them useless is noise.
  const auto exact = test::simulate_presses(truth_, poses, 0.0, rng_);
  const auto r = calibration::calibrate_plate(nominal_, kBoard, exact, no_tilt_check);
  EXPECT_NEAR(r.plate.mu_silicone, 1.45, 1e-6);
}

TEST_F(CalibrationRefusals, OneTiltedPressAmongFlatOnesIsAccepted) {
  auto poses = test::flat_poses(5);
  poses[2].tilt_deg = {15, 0};
  const auto presses = test::simulate_presses(truth_, poses, 0.0, rng_);
  const auto r = calibration::calibrate_plate(nominal_, kBoard, presses);
  EXPECT_GT(r.max_board_tilt_deg, 10);
  EXPECT_NEAR(r.plate.mu_silicone, 1.45, 1e-6);
}

TEST_F(CalibrationRefusals, TooFewCornersAreRefused) {
  const auto poses = simulation::random_board_poses(4, 25.0, {4, 10}, rng_);
  auto presses = test::simulate_presses(truth_, poses, 0.1, rng_);
  auto sparse = presses;
  sparse[1].corners.resize(5);
  std::string why = refusal(nominal_, kBoard, sparse);
  EXPECT_TRUE(has(why, "press 1: 5 corners")) << why;

  calibration::PlateCalibrationOptions strict;
  strict.min_total_corners = 10000;
  why = refusal(nominal_, kBoard, presses, strict);
  EXPECT_TRUE(has(why, "corners in all")) << why;

  why = refusal(nominal_, kBoard, {presses[0]});
  EXPECT_TRUE(has(why, "1 given")) << why;

  // Enough corners, but all in one row: no right angle to measure.
  auto one_row = presses;
  calibration::PressCorners row;
  for (int col = 0; col < kBoard.cols; ++col) row.corners.push_back({col, {600.0 + 10 * col, 300}, {500.0 + 10 * col, 300}});
  one_row[0] = row;
  calibration::PlateCalibrationOptions loose;
  loose.min_corners_per_press = 4;
  why = refusal(nominal_, kBoard, one_row, loose);
  EXPECT_TRUE(has(why, "press 0: no corner has both a row and a column neighbour")) << why;
}

TEST_F(CalibrationRefusals, BoardThatDoesNotFitTheCornersIsRefused) {
  const auto poses = simulation::random_board_poses(4, 25.0, {6, 10}, rng_);
  const auto presses = test::simulate_presses(truth_, poses, 0.1, rng_);
  calibration::Checkerboard wrong_square = kBoard;
  wrong_square.square_mm = 5.5;
  EXPECT_TRUE(has(refusal(nominal_, wrong_square, presses), "square_mm do not fit"));
  // cols and rows swapped: ids land on the wrong neighbours.
  const calibration::Checkerboard swapped{kBoard.rows, kBoard.cols, kBoard.square_mm};
  EXPECT_TRUE(has(refusal(nominal_, swapped, presses), "board_corners [6, 8]"));
  EXPECT_THROW(calibration::calibrate_plate(nominal_, {1, 6, 4.0}, presses), InputError);
}

TEST_F(CalibrationRefusals, MarkerSetsWithCornersOffTheBoardAreRefused) {
  MarkerSet set;
  set.left = {{{600, 300}, 48, 1}};
  set.right = {{{500, 300}, 48, 1}};
  set.matches = {{0, 0, 48}};
  try {
    calibration::press_corners_from(set, kBoard, "press 3");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), "press 3, match 0: corner id 48 is not on a board of 8 x 6")) << e.what();
  }
  set.matches = {{0, 1, 48}};
  EXPECT_THROW(calibration::press_corners_from(set, kBoard, "p"), InputError);  // right index out of range
  set.left = {{{600, 300}, 4, 1}, {{610, 300}, 4, 1}};
  set.right = {{{500, 300}, 4, 1}, {{510, 300}, 4, 1}};
  set.matches = {{0, 0, 4}, {1, 1, 4}};
  EXPECT_THROW(calibration::press_corners_from(set, kBoard, "p"), InputError);  // id twice
}

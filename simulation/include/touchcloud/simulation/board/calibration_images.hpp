// A calibration set rendered with a known sensor: stereo images of a board
// held in air in front of the cameras (for Zhang's step) and of a board
// pressed into the gel (for the refractive step), with the poses used. What
// a user photographs for calibrate_from_images.yaml, with the truth known.
#pragma once

#include <random>
#include <vector>

#include <opencv2/core.hpp>

#include "touchcloud/simulation/board/board_image.hpp"
#include "touchcloud/simulation/board/board_press.hpp"
#include "touchcloud/sensor/gelstereo_sensor.hpp"

namespace touchcloud::simulation {

struct CalibrationImageOptions {
  sensor::Checkerboard air_board{9, 6, 10.0};   // printed, held 120-200 mm from the cameras
  int air_pairs = 12;
  double air_max_tilt_deg = 35;
  sensor::Checkerboard press_board{6, 5, 3.5};  // small enough to lie in the gel whole
  int press_pairs = 16;
  double press_max_tilt_deg = 25;
  Eigen::Vector2d press_depth_range_mm{8.0, 11.0};
  BoardLook look;
};

struct StereoImages {
  cv::Mat left, right;
};

struct CalibrationImages {
  std::vector<StereoImages> air, press;
  std::vector<BoardPlacement> air_placements;  // left camera frame
  std::vector<BoardPose> press_poses;          // sensor frame
};

// Poses are drawn from `rng` until every corner, with the board's paper
// around it, is in both images (and, pressed, inside the gel).
CalibrationImages render_calibration_images(const sensor::GelStereoSensor& truth,
                                            const CalibrationImageOptions& options, std::mt19937_64& rng);

}  // namespace touchcloud::simulation

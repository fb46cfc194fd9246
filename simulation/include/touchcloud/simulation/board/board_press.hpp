// A checkerboard pressed flat into the GelStereo gel, as calibration images
// would show it: the board's inner corners in the sensor frame and their
// pixels in both views through the refracting plate. Stands in for
// cv::findChessboardCorners on real images. Lengths in mm, angles in degrees.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/sensor/checkerboard.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::simulation {

inline constexpr double kRadiansPerDegree = M_PI / 180.0;

// One press. The board plane is tilted by tilt_deg (about the sensor x axis,
// then y) and sits depth_mm deep in the gel hemisphere: its distance from the
// hemisphere's centre is radius - depth_mm, whatever the tilt. spin_deg turns
// the board in its plane; shift_mm moves its centre in the plane.
struct BoardPose {
  Eigen::Vector2d tilt_deg = Eigen::Vector2d::Zero();
  double depth_mm = 6.0;
  double spin_deg = 0.0;
  Eigen::Vector2d shift_mm = Eigen::Vector2d::Zero();
};

// Every inner corner of the board in the sensor frame, by id (row-major).
std::vector<Eigen::Vector3d> board_corners_sensor(const sensor::Checkerboard& board, const BoardPose& pose,
                                                  double gel_radius_mm);

struct PressImaging {
  double noise_px = 0.1;           // Gaussian sigma per pixel coordinate
  double min_height_mm = 0.5;      // corners closer to the gel face are not pressed into the gel
};

// The corners inside the hemisphere, at least min_height_mm above the gel
// face and imaged by both cameras of `rig` (the true rig), with Gaussian
// pixel noise from `rng`. Markers carry the corner id; matches pair them.
MarkerSetPtr image_press(const optics::StereoRig& rig, const Eigen::Isometry3d& left_from_sensor,
                         const std::vector<Eigen::Vector3d>& corners_sensor, double gel_radius_mm,
                         const PressImaging& imaging, std::mt19937_64& rng);

// `count` poses with the tilt's size uniform in [0, max_tilt_deg] in a
// uniformly random direction, depth uniform in depth_range_mm, spin in
// [-20, 20] deg and a shift of up to 2 mm.
std::vector<BoardPose> random_board_poses(int count, double max_tilt_deg, const Eigen::Vector2d& depth_range_mm,
                                          std::mt19937_64& rng);

}  // namespace touchcloud::simulation

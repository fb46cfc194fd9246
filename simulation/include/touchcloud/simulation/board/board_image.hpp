// Images of a printed checkerboard as a camera sees it, for testing corner
// detection and calibration against known truth: in air through a lens, or
// pressed into the gel and seen through the plate. Each pixel is traced to
// the board plane (no forward-projection shortcut), so lens distortion and
// refraction bend the squares' edges as they would; edges are anti-aliased
// by the pixel's footprint on the board, which keeps every corner's saddle
// point where its true projection is. Lengths in mm, grey levels 0-255.
#pragma once

#include <functional>
#include <optional>
#include <random>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "touchcloud/optics/stereo_rig.hpp"
#include "touchcloud/sensor/checkerboard.hpp"

namespace touchcloud::simulation {

// The board in some 3D frame: inner corner 0 at `corner0_mm`, unit axes along
// its columns and rows. The square diagonally outside corner 0 is black.
struct BoardPlacement {
  Eigen::Vector3d corner0_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d along_cols = Eigen::Vector3d::UnitX(), along_rows = Eigen::Vector3d::UnitY();
};

struct BoardLook {
  double black = 35, white = 215;      // printed squares and the paper
  double background = 110;             // what is not the board
  double margin_squares = 1.0;         // white paper around the squares
  double noise_grey = 1.0;             // Gaussian sigma per pixel
};

struct PixelRay {
  Eigen::Vector3d origin_mm, direction;
};

// How one camera sees the frame the board is placed in.
struct BoardCamera {
  int width_px = 0, height_px = 0;
  std::function<std::optional<PixelRay>(const Eigen::Vector2d& pixel_px)> ray;       // nothing: no ray
  std::function<std::optional<Eigen::Vector2d>(const Eigen::Vector3d& point_mm)> pixel;  // nothing: not imaged
  std::function<bool(const Eigen::Vector3d& point_mm)> board_seen = [](const Eigen::Vector3d&) { return true; };
};

// A camera in air; the frame is `camera_from_frame`'s.
BoardCamera camera_in_air(const optics::PinholeCamera& camera, const Eigen::Isometry3d& camera_from_frame);

// One camera of `rig` looking through the plate into the gel; the frame is
// the left camera's. Only board points inside the gel hemisphere
// (`left_from_sensor`, radius) are seen; elsewhere the camera sees gel.
BoardCamera camera_through_plate(const optics::StereoRig& rig, optics::StereoSide side,
                                 const Eigen::Isometry3d& left_from_sensor, double gel_radius_mm);

// The 8-bit grey image of the board. Pixels whose rays cannot reach the
// board's surroundings are traced only inside the board's outline.
cv::Mat render_board(const BoardCamera& camera, const sensor::Checkerboard& board, const BoardPlacement& placement,
                     const BoardLook& look, std::mt19937_64& rng);

// Every inner corner's position (by id) for a placement.
std::vector<Eigen::Vector3d> placed_corners(const sensor::Checkerboard& board, const BoardPlacement& placement);

}  // namespace touchcloud::simulation

// The calibration objective of one press (the paper's Eq. 1, no board pose):
// triangulate every corner through a candidate plate (RSRT) and compare the
// board's shape with a flat grid of square_mm squares — distances between
// corners, and right angles between the row and column directions.
//
// Which distances: neighbours only (the paper's choice) carry a bias from
// pixel noise, E|d + e| - d ~ sigma_perp^2 / (2 d), about 4e-4 mm at 0.1 px
// for 4 mm squares, while a plate 1 mm and 2 deg off changes them by only
// ~0.01 mm: at 0.1 px that bias moves mu_silicone by ~0.01. The bias falls as
// 1/d and the signal grows as d, so by default every pair of corners is
// compared (distances up to the board's diagonal), and the right angle at each
// corner is taken between its row's and its column's farthest corners. In
// simulation (8 x 6 corners, 20 presses, 0.1 px) neighbours leave mu_silicone
// ~0.008 low, rows and columns ~0.002, all pairs ~0.001.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "touchcloud/calibration/press_corners.hpp"
#include "touchcloud/optics/stereo_rig.hpp"

namespace touchcloud::calibration {

// What of a press does not depend on the plate: each corner's air ray
// direction from both camera centres (left camera frame), and which corners
// are neighbours on the board. Indices refer to `ids`.
enum class BoardSpans {
  Neighbours,      // next corner in the row and column (plus diagonals when asked)
  RowsAndColumns,  // every pair of corners in one row or one column (plus diagonals when asked)
  AllPairs,        // every pair of corners
};

// Two corners and their distance on the board, in squares.
struct CornerSpan {
  int i = 0, j = 0;
  double squares = 1;
};

struct BoardRays {
  std::vector<int> ids;
  std::vector<Eigen::Vector3d> left_direction, right_direction;  // unit, left frame
  Eigen::Vector3d right_centre_mm = Eigen::Vector3d::Zero();     // left frame
  std::vector<std::array<int, 2>> edges;  // next corner in the row or column: the error metric
  std::vector<CornerSpan> spans;          // the distances fitted
  std::vector<std::array<int, 3>> right_angles;  // corner, one along its row, one along its column

  int residual_count() const { return static_cast<int>(spans.size() + right_angles.size()); }
};

// InputError naming `what` and the corner when a pixel is off the image or
// cannot be undistorted.
BoardRays board_rays(const optics::StereoRig& rig, const Checkerboard& board, const PressCorners& press,
                     BoardSpans spans, bool with_diagonals, const std::string& what);

// The plate is physically possible for these cameras (both centres in air,
// positive indices): the solver's steps must stay there.
bool plate_admissible(const optics::RefractivePlate& plate, const Eigen::Vector3d& right_centre_mm);

// Corner positions (left frame, mm) through `plate`. False, with the reason in
// `failure` when given, when a ray does not reach the silicone or the pair
// does not triangulate.
bool triangulate_board(const BoardRays& rays, const optics::RefractivePlate& plate,
                       std::vector<Eigen::Vector3d>& points_mm, std::string* failure = nullptr);

// residual_count() residuals, in mm: distance errors of the spans, then the
// cosine of each right angle times square_mm.
void board_residuals(const BoardRays& rays, const std::vector<Eigen::Vector3d>& points_mm, double square_mm,
                     double* residuals);


// The angle (deg) between the board's best-fit plane and the plate.
double board_tilt_deg(const std::vector<Eigen::Vector3d>& points_mm, const Eigen::Vector3d& plate_normal);

}  // namespace touchcloud::calibration

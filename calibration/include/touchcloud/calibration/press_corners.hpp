// The corners one press of the calibration checkerboard gives: matched
// left/right pixels of the board's inner corners, by corner id.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "touchcloud/sensor/checkerboard.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud::calibration {

using sensor::Checkerboard;

struct CornerPair {
  int id = -1;  // corner index, row-major
  Eigen::Vector2d left_px = Eigen::Vector2d::Zero(), right_px = Eigen::Vector2d::Zero();
};

// One press: the corners seen by both cameras (some may be missing).
struct PressCorners {
  std::vector<CornerPair> corners;
};

// The matched corners of a MarkerSet (match.id, or the left marker's id when
// match.id is -1, is the corner index). InputError, naming `what`, for a
// match index out of range, a corner id outside the board, an id seen twice
// or left and right ids that disagree.
PressCorners press_corners_from(const MarkerSet& markers, const Checkerboard& board, const std::string& what);

}  // namespace touchcloud::calibration

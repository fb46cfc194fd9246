// Inner corners of a checkerboard in one grey image: OpenCV's chessboard
// detector, sub-pixel refinement (cv::cornerSubPix), then the corners put in
// the board's own order so that both cameras and every image agree on ids.
//
// The board's order: corner id = row * cols + col, seen from the printed
// side with cols running right and rows down, and the square diagonally
// outside corner 0 black. A board that looks the same turned by 180 deg
// (cols + rows even) cannot be put in that order from an image: refused.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "touchcloud/sensor/checkerboard.hpp"

namespace touchcloud::imaging {

enum class ChessboardDetector { Classic, SectorBased };

struct CornerSearch {
  ChessboardDetector detector = ChessboardDetector::Classic;
  int refine_half_window_px = 5;  // cornerSubPix's half window: below half a square's edge in the image
};

// InputError when cols + rows is even (the board's turn is ambiguous).
void require_oriented_board(const sensor::Checkerboard& board);

// The board's corners in `grey` (8-bit, one channel) by id, or nothing when
// the detector does not find all cols x rows of them.
std::optional<std::vector<Eigen::Vector2d>> find_board_corners(const cv::Mat& grey, const sensor::Checkerboard& board,
                                                               const CornerSearch& search);

}  // namespace touchcloud::imaging

// Checkerboard corners found in calibration images: one entry per stereo
// pair, the corners of both views matched by corner id (row * cols + col).
// What board_image_corners gives and the calibration stages read; no OpenCV.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "touchcloud/data_type_name.hpp"
#include "touchcloud/types/marker_set.hpp"

namespace touchcloud {

struct BoardView {
  std::string left_file, right_file;  // where the corners were found
  MarkerSetPtr corners;               // matched left/right corners; id = corner index
};

struct BoardViews {
  int width_px = 0, height_px = 0;  // every image has this size
  int cols = 0, rows = 0;           // inner corners of the board that was searched for
  std::vector<BoardView> views;
};
using BoardViewsPtr = std::shared_ptr<const BoardViews>;

}  // namespace touchcloud

TOUCHCLOUD_DATA_TYPE(touchcloud::BoardViewsPtr, "board_views");

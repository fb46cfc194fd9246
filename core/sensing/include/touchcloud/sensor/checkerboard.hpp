// The checkerboard of refractive calibration: what the press simulator
// images and what the calibration fits. Inner corners cols x rows, corner
// id = row * cols + col; lengths in mm.
#pragma once

#include <array>

#include <vector>

namespace touchcloud::sensor {

struct Checkerboard {
  int cols = 8, rows = 6;  // inner corners
  double square_mm = 4.0;  // edge of one square

  int corner_count() const { return cols * rows; }
  // InputError naming the field when the board makes no sense.
  void validate() const;

  // From a stage's parameters `board_corners` [cols, rows] and `square_mm`;
  // ParameterError naming the parameter when they are not a valid board.
  static Checkerboard from_parameters(const std::array<int, 2>& board_corners, double square_mm);
};

}  // namespace touchcloud::sensor

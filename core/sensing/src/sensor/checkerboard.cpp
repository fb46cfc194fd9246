#include "touchcloud/sensor/checkerboard.hpp"
#include "touchcloud/number_text.hpp"

#include <cmath>
#include <string>

#include "touchcloud/error.hpp"

namespace touchcloud::sensor {

void Checkerboard::validate() const {
  if (cols < 2 || rows < 2)
    throw InputError("board: needs at least 2 x 2 inner corners, got [" + std::to_string(cols) + ", " +
                     std::to_string(rows) + "] ([cols, rows])");
  if (!(square_mm > 0)) throw InputError("board: square_mm must be > 0, got " + number_text(square_mm));
}

Checkerboard Checkerboard::from_parameters(const std::vector<double>& board_corners, double square_mm) {
  if (board_corners.size() != 2) throw ParameterError("board_corners", "must be [cols, rows]");
  for (double v : board_corners)
    if (v != std::floor(v)) throw ParameterError("board_corners", "must be whole numbers [cols, rows]");
  if (!(square_mm > 0)) throw ParameterError("square_mm", "must be > 0");
  const Checkerboard board{static_cast<int>(board_corners[0]), static_cast<int>(board_corners[1]), square_mm};
  try {
    board.validate();
  } catch (const InputError& e) {
    throw ParameterError("board_corners", e.what());
  }
  return board;
}

}  // namespace touchcloud::sensor
